#pragma once
// The scene as kernels see it: the Embree-built BVH, triangles, materials and spectra in device
// buffers, and the preprocessor definitions that specialise kernels to this scene.
#include <functional>
#include <string>
#include <vector>

#include "geometry/alpha_cutouts.h"
#include "geometry/bvh.h"
#include "geometry/instanced_bvh.h"
#include "opencl/device.h"
#include "opencl/kernel_program.h"
#include "render/device_media.h"
#include "render/light_bvh.h"
#include "scene/scene.h"

namespace kasha {

struct BinnedObserver;

// Host-side arrays in kernel layout; cheap to build, so `kasha info` uses them for its figures.
struct KernelSceneData {
  FlatBvh bvh;
  KCamera camera;
  float bin_nm;
  std::vector<KMaterial> materials;
  std::vector<float> spectra;            // N zeros, then material spectra at KMaterial offsets
  std::vector<float> lobes;              // gloss lobe tables at KMaterial::lobe
  std::vector<float> emitter_radiance;   // emitters x N, then the lights' spectra x N
  std::vector<KLight> lights;            // the lights that are not triangles
  std::vector<KTexture> textures;        // per texture and use (kernels/materials/texture.h)
  std::vector<KTexOp> tex_ops;           // texture programs' steps (shared/texture_program.h)
  std::vector<KTexcoords> texcoords;     // per leaf triangle, when the scene has textures
  std::vector<KShadingNormals> normals;  // per leaf triangle, when some shape has shading normals
  // Per leaf triangle, when some rough material is anisotropic or some material normal-mapped.
  std::vector<KTangent> tangents;
  // Light sampling: emitting triangles (leaf order), then the other lights (~index into
  // `lights`), with the CDF of their power, and per emitter the area density
  // p(triangle)/area = pi·Σ Le Δλ / total power (light paths'). Next-event estimation picks
  // within the emitting triangles' share by the light BVH (render/light_bvh.h), given the point.
  std::vector<int> light_tri;
  std::vector<float> light_cdf;
  std::vector<float> emitter_area_pdf;
  int light_triangles = 0;  // the first entries of light_tri
  // Per emitting triangle, its sphere light (radius 0: none); empty without sphere lights.
  std::vector<KSphereLight> light_spheres;
  LightBvh light_bvh;
  DeviceMedia media;  // participating media (docs/media.md); empty without them
  int camera_medium = -1;
  double total_power = 0;  // W: Σ over emitting triangles of area·pi·Σ Le Δλ and the lights' power

  explicit KernelSceneData(const Scene& scene);
  size_t bytes() const;

 private:
  KMaterial kernel_material(const Material& m, const Scene& scene, const BinnedObserver& obs);
  void add_coat(const CoatDesc& coat, KMaterial& k);
  void add_lambert_shape(const CoatDesc& c, const std::vector<double>& t, KMaterial& k);
  // What a texture is used as: a reflectance (spectral), a concentration (a number in [0, 1])
  // or an emission factor (a number ≥ 0).
  enum class TextureUse { reflectance, concentration, emission };
  KTexture image_texture(const RgbImage& image, TextureWrap wrap, bool bilinear, TextureUse use,
                         const Scene& scene);
  KTexture plain_texture(const Texture& t, TextureUse use, const Scene& scene);
  void add_textures(const Scene& scene);
  std::vector<int> alpha_textures(const Scene& scene,
                                  const std::function<int(int)>& scalar_texture);
  void add_normal_maps(const Scene& scene);
  void add_shading_normals(const Scene& scene);
  void add_tangents(const Scene& scene);
  void add_light_sampling(const Scene& scene);
  static KLight kernel_light(const Light& l, int spectrum, const Eigen::Vector3d& centre,
                             double radius);
  void add_environment(const Light& l, const Scene& scene, KLight& kl);
  int bin_centres(const Scene& scene);
  int lambda_ = -1;
};

// The scene's alpha cut-outs in scene order, for the host's traversals (empty without any).
AlphaCutouts alpha_cutouts(const KernelSceneData& data);

// The lobe table of a gloss part: KASHA_LOBE_CELLS ring densities (per solid angle), then their
// CDF. The tabulated profile is averaged over each ring (a uniform cone without a profile).
std::vector<float> gloss_lobe_table(const GlossDesc& gloss);

// Floats of scratch spectra each work item gets (KASHA_SCRATCH_FLOATS): the bins where an
// environment image's texel radiance is computed, else 0.
int scratch_floats(const Scene& scene);

// Definitions every kernel of this scene is built with.
KernelDefines scene_defines(const Scene& scene, bool spectral_film);

class DeviceScene {
 public:
  DeviceScene(ClContext& cl, const Scene& scene);
  const KernelSceneData& data() const { return data_; }
  // Sets KASHA_SCENE_PARAMS (kernels/geometry/scene_view.h) as kernel arguments from `first` on:
  // the parameters, the tables buffer, and scratch for `items` work items; returns the next
  // argument's index.
  int bind(cl::Kernel& kernel, int first, size_t items);

 private:
  KernelSceneData data_;
  ClContext& cl_;
  KSceneParams params_{};  // the camera, counts and each table's offset in tables_
  cl::Buffer tables_;      // every table of data_, uploaded once
  int scratch_floats_ = 0;
  cl::Buffer scratch_;
  size_t scratch_bytes_ = 0;
};

}  // namespace kasha
