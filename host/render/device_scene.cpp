#include "render/device_scene.h"

#include "color/cie_observer.h"

namespace kasha {

static int append(std::vector<float>& out, const std::vector<double>& values) {
  if (values.empty()) return -1;
  int offset = static_cast<int>(out.size());
  for (double v : values) out.push_back(static_cast<float>(v));
  return offset;
}

// The colour of a material's Lambert parts under equal-energy light, fluorescence included:
// per nm, r_i = ρ_i + ê_i Σ_j a_j; normalized so a perfect white has Y = 1.
static void albedo_xyz(const Material& m, const WavelengthGrid& grid, const BinnedObserver& obs,
                       float out[3]) {
  double yield = 0;
  for (double a : m.a) yield += a;
  std::vector<double> r(grid.bins, 0.0);
  for (int i = 0; i < grid.bins; ++i) {
    if (!m.rho.empty()) r[i] += m.rho[i];
    if (!m.e_hat.empty()) r[i] += m.e_hat[i] * yield;
  }
  double white = 0;
  for (int i = 0; i < grid.bins; ++i) white += obs.y[i];
  auto xyz = obs.xyz(r, 1.0);
  for (int k = 0; k < 3; ++k) out[k] = white > 0 ? static_cast<float>(xyz[k] / white) : 0.0f;
}

KernelSceneData::KernelSceneData(const Scene& scene) : bvh(build_bvh(scene.triangles)) {
  BinnedObserver obs(scene.grid);
  for (const Material& m : scene.materials) {
    KMaterial k{};
    k.passive = append(spectra, m.rho);
    k.excitation = append(spectra, m.a);
    k.emission = append(spectra, m.e_hat);
    k.gloss = static_cast<float>(m.gloss_reflectance());
    albedo_xyz(m, scene.grid, obs, k.albedo_xyz);
    materials.push_back(k);
  }
  for (const Emitter& e : scene.emitters) append(emitter_radiance, e.per_bin);
}

size_t KernelSceneData::bytes() const {
  return bvh.nodes.size() * sizeof(KBvhNode) + bvh.triangles.size() * sizeof(KTriangle) +
         materials.size() * sizeof(KMaterial) +
         (spectra.size() + emitter_radiance.size()) * sizeof(float);
}

KernelDefines scene_defines(const Scene& scene, bool spectral_film) {
  KernelDefines d;
  d["KASHA_BINS"] = std::to_string(scene.grid.bins);
  d["KASHA_SPECTRAL_FILM"] = spectral_film ? "1" : "0";
  d["KASHA_FILM_ROWS"] = std::to_string(spectral_film ? scene.grid.bins : 3);
  d["KASHA_FLUORESCENCE"] = scene.fluorescent() ? "1" : "0";
  d["KASHA_GLOSS"] = scene.glossy() ? "1" : "0";
  return d;
}

// OpenCL rejects zero-sized buffers; an absent table gets one element that is never read.
template <typename T>
static cl::Buffer upload(ClContext& cl, const std::vector<T>& v) {
  size_t bytes = std::max<size_t>(sizeof(T), v.size() * sizeof(T));
  cl::Buffer b(cl.context(), CL_MEM_READ_ONLY, bytes);
  if (!v.empty()) cl.queue().enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
  return b;
}

DeviceScene::DeviceScene(ClContext& cl, const Scene& scene) : data_(scene) {
  nodes = upload(cl, data_.bvh.nodes);
  triangles = upload(cl, data_.bvh.triangles);
  materials = upload(cl, data_.materials);
  spectra = upload(cl, data_.spectra);
  emitter_radiance = upload(cl, data_.emitter_radiance);
}

}  // namespace kasha
