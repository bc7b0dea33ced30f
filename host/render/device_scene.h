#pragma once
// The scene as kernels see it: the Embree-built BVH, triangles, materials and spectra in device
// buffers, and the preprocessor definitions that specialise kernels to this scene.
#include <string>
#include <vector>

#include "geometry/bvh.h"
#include "opencl/device.h"
#include "opencl/kernel_program.h"
#include "scene/scene.h"

namespace kasha {

// Host-side arrays in kernel layout; cheap to build, so `kasha info` uses them for its figures.
struct KernelSceneData {
  FlatBvh bvh;
  std::vector<KMaterial> materials;
  std::vector<float> spectra;           // material spectra at KMaterial offsets
  std::vector<float> emitter_radiance;  // emitters x N

  explicit KernelSceneData(const Scene& scene);
  size_t bytes() const;
};

// Definitions every kernel of this scene is built with.
KernelDefines scene_defines(const Scene& scene, bool spectral_film);

class DeviceScene {
 public:
  DeviceScene(ClContext& cl, const Scene& scene);
  const KernelSceneData& data() const { return data_; }

  cl::Buffer nodes, triangles, materials, spectra, emitter_radiance;

 private:
  KernelSceneData data_;
};

}  // namespace kasha
