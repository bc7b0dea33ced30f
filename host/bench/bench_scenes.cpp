#include "bench/bench_scenes.h"

#include <algorithm>

#include "render/integrator_registry.h"

namespace kasha {

const std::vector<BenchScene>& bench_scenes() {
  // Bounds (README, "kasha bench"): the smaller of a third of the least validation error a wrong
  // image (π or 1/π times the reference, black, a film row missing) has on the scene, and 100
  // times the largest a 2-second run had on a 2-core PoCL CPU device (three runs of each).
  static const std::vector<BenchScene> scenes = {
      {"cornell_box", "cornell_box.json", 128, 128, "bench/cornell_box.reference.exr", false, 1e-4},
      {"furnace_fluorescent", "furnace_fluorescent.json", 32, 32, "furnace", false, 1e-3},
      {"mirror_caustic", "mirror_caustic.json", 64, 64, "bench/mirror_caustic.reference.exr", true,
       0.1, {"bpt"}},
      {"million_triangles", "million_triangles.json", 128, 128,
       "bench/million_triangles.reference.exr", false, 2e-4},
  };
  return scenes;
}

std::vector<std::string> bench_integrators(const BenchScene& scene) {
  std::vector<std::string> out;
  auto listed = [&](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  // Not run on any scene: an integrator that takes direct light by merges (ppm, a baseline for
  // comparing techniques): a 2-second run's bias (its global radius) is above every scene's bound
  // (5 % relMSE of the Cornell box's 16 × 16 blocks against 10⁻⁴).
  for (const std::string& name : IntegratorRegistry::names(true))
    if ((!scene.camera_sees_mirror || IntegratorRegistry::find(name).traits.sees_camera_mirrors) &&
        !IntegratorRegistry::find(name).traits.direct_by_merges && !listed(scene.left_out, name))
      out.push_back(name);
  return out;
}

std::string default_bench_scenes_dir() {
  return KASHA_SCENES_DIR;
}

}  // namespace kasha
