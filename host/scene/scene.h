#pragma once
// A scene as loaded from its JSON file (docs/formats.md#scenes): camera, materials on the chosen
// wavelength grid, and every shape turned into triangles.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/instances.h"
#include "material/material.h"
#include "scene/camera.h"
#include "scene/light.h"
#include "scene/medium.h"
#include "scene/normal_map.h"
#include "scene/pbrt/pbrt_import.h"
#include "scene/shape_mesh.h"
#include "scene/sphere_light.h"
#include "scene/texture.h"
#include "shared/shared_types.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

struct Emitter {
  std::string where;                           // JSON path of the shape's "emission"
  SpectrumPtr radiance;                        // Lambertian spectral radiance, front side only
  std::vector<double> per_bin;                 // on the scene grid
  int first_triangle = 0, triangle_count = 0;  // in scene (primitive) order
  int texture = -1;         // the scene texture multiplying the radiance (docs/textures.md)
  double texture_mean = 1;  // its mean over its image or squares: light sampling's weight

  // Σ_i L_i·Δλ: the radiance integrated over the grid (W·m⁻²·sr⁻¹).
  double integrated_radiance(double bin_nm) const;
};

// π·A·∫L: the power a Lambertian emitter of integrated radiance `radiance` sends from the front of
// `t` (its float vertices, as the kernels see them). The light CDF and the load check share it.
double emitted_power(const KTriangle& t, double radiance);

// The material of the shapes that are only boundaries of media ("interface": true).
constexpr const char* kInterfaceMaterial = "(interface)";

struct ShapeInfo {
  std::string type;  // obj, quad, box, sphere
  bool inward = false;
  int material = -1, emitter = -1;
  int first_triangle = 0, triangle_count = 0;  // in scene (primitive) order
  // Its "alpha" cut-out (docs/formats.md#alpha): a constant, or a scene texture's value (-1: none).
  double alpha = 1;
  int alpha_texture = -1;
  // An emitting sphere that next-event estimation samples as one light (scene/sphere_light.h).
  std::optional<SphereBound> sphere_light;
  MediumInterface medium;  // its "medium" (docs/media.md); vacuum on both sides by default
  bool cut_out() const { return alpha < 1 || alpha_texture >= 0; }
};

struct Scene {
  std::string file;
  Camera camera;
  WavelengthGrid grid;
  std::vector<MaterialDesc> material_descs;
  std::vector<Material> materials;                  // on `grid`, same order as material_descs
  std::vector<Texture> textures;                    // the scene's "textures"
  std::vector<MaterialTextures> material_textures;  // same order as material_descs
  std::vector<NormalMap> normal_maps;               // the materials' "normal_map" images
  std::vector<KTriangle> triangles;                 // scene order: prim == index
  std::vector<TriangleUv> uvs;  // the triangles' texture coordinates, scene order
  // The triangles' shading normals, scene order; empty unless some shape has them (OBJ `vn`).
  std::vector<TriangleNormals> normals;
  std::vector<Emitter> emitters;
  std::vector<Light> lights;      // the "lights" that are not shapes
  // Participating media (docs/media.md): as given, on the grid, and which one the camera is in.
  std::vector<MediumDesc> medium_descs;
  std::vector<Medium> media;
  int camera_medium = -1;
  std::vector<int> light_media;  // per light, the medium it is in (-1: vacuum)
  // Per triangle (scene order), its shape's medium interface; empty when no shape has one.
  std::vector<MediumInterface> triangle_media;
  std::vector<ShapeInfo> shapes;  // the scene's own, then the objects' (triangles in that order)
  // Object instancing (docs/formats.md#instances): an object placed more than once keeps one
  // copy of its triangles, after the scene's own, and each placement; `object_names` by object.
  SceneInstances instances;
  std::vector<std::string> object_names;
  // Switchable lamps (the scene's "lamps"): their names, and the one that is on.
  std::vector<std::string> lamp_names;
  std::string lamp;
  // "max_depth": the scattering vertices a counted path may have as the scene's author rendered it
  // (pbrt-v4's Integrator maxdepth, which the import writes): what `--max-depth scene` uses.
  std::optional<int> max_depth;

  bool fluorescent() const;  // some shape's material has a fluorescent part, or a used medium a dye
  bool glossy() const;                 // some shape's material has a gloss lobe
  bool uses(MaterialKind kind) const;  // some shape's material is of this kind
  bool dispersive() const;             // some shape's material is a dispersive dielectric
  bool rough() const;                  // some shape's material is a rough dielectric or conductor
  bool anisotropic() const;            // ... with alpha_x != alpha_y (its frame follows ∂p/∂u)
  bool coated() const;                 // some shape's material has a coat
  bool transmissive() const;           // some shape's material transmits diffusely
  bool thin() const;                   // some shape's material is a thin dielectric
  bool mixed() const;                  // some shape's material is a mix (docs/materials.md#mixes)
  bool shading_normals() const { return !normals.empty(); }  // some shape has them
  // Some ray can travel in a medium: the camera or a light is in one, or a shape bounds one.
  bool has_media() const;
  std::vector<bool> used_media() const;  // per medium: something is in it (a shape's side, ...)
  bool scattering() const;               // some used medium scatters in some bin
  int emitting_medium() const;           // the first used medium that emits, -1: none
  bool normal_mapped() const;  // some shape's material has a normal map (its ∂p/∂u frame)
  // Some used material scatters by a delta lobe: an ideal mirror, a smooth dielectric or
  // conductor, or a smooth coat's reflection.
  bool has_delta_surfaces() const;
  // Some used mix picks a material that scatters by a delta lobe on part of its surface: photons
  // are stored only on the other part, so merging estimates there fall short
  // (docs/materials.md#mixes).
  bool mixes_delta() const;
  int material_index(const std::string& name) const;  // -1 when absent
  bool has_light(LightType type) const;
  bool has_environment() const;     // some infinite light has an image
  bool textured() const;            // some shape's material carries a texture
  bool emission_textured() const;   // some emitter's radiance is multiplied by a texture
  bool roughness_textured() const;  // some rough material's roughness is a texture's value
  // Some conductor's roughness texture may be smooth (a delta lobe) somewhere.
  bool partly_smooth_conductor() const;
  bool cut_out() const;  // some shape has an alpha cut-out
  // The bounding sphere of the triangles as placed (as the kernels see them), where distant and
  // infinite lights send their photons from.
  void bounding_sphere(Eigen::Vector3d& centre, double& radius) const;
  // Whether the material of some shape has the property (unused materials do not count; a used
  // mix's materials do).
  bool any_used(const std::function<bool(const Material&)>& has) const;
  // The indices of the materials shapes use, a used mix's materials included.
  std::vector<int> used_materials() const;
  // Triangles as the renders see them: each placement's object counted again.
  size_t placed_triangles() const;
  // The triangle of a hit (KHit::instance numbered as the kernels' instances: the scene's own
  // triangles first when there are instances) as placed in the world.
  KTriangle hit_triangle(const KHit& hit) const;
  // A normal of the hit's triangle (a shading normal) carried into the world, not normalised.
  Eigen::Vector3d hit_normal(const KHit& hit, const Eigen::Vector3d& n) const;
};

// `grid`, when given, replaces the scene's own "wavelengths" (the same scene on another grid);
// `lamp`, when not empty, switches on that lamp of the scene's "lamps" instead of its "lamp".
// A `.pbrt` path is a pbrt-v4 scene (docs/pbrt-import.md); `materials` replace named materials
// (--material NAME=FILE).
Scene load_scene(const std::string& path, const std::optional<GridRequest>& grid = std::nullopt,
                 const std::string& lamp = "", const std::vector<MaterialOverride>& materials = {});

}  // namespace kasha
