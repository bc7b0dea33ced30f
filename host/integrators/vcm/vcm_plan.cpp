#include "integrators/vcm/vcm_plan.h"

#include <algorithm>

#include "geometry/embree_scene.h"
#include "integrators/vcm/seen_light.h"

namespace kasha {

size_t default_light_paths(VcmMode m, size_t pixels, bool caustic_lit, bool scattering) {
  if (m == VcmMode::ppm) return std::max<size_t>(pixels, kLeastPhotonMappingPaths);
  if (m == VcmMode::vcm && caustic_lit)
    return std::min<size_t>(pixels * kCausticLitLightPaths, (1u << 31) - 1);
  if (m == VcmMode::vcm && scattering)
    return std::min<size_t>(pixels * kScatteringLightPaths, (1u << 31) - 1);
  return pixels;
}

int default_camera_paths(VcmMode m, const Scene& scene, bool caustic_lit) {
  if (m == VcmMode::ppm) return kDefaultPhotonMappingCameraPaths;
  if (m == VcmMode::vcm && caustic_lit) return kCausticLitCameraPaths;
  return scene.has_delta_surfaces() ? kCausticCameraPaths : kDefaultCameraPaths;
}

VcmPlan plan_for(VcmMode m, const IntegratorSetup& s) {
  VcmPlan p;
  const EmbreeScene embree(s.scene.triangles, AlphaCutouts(), s.scene.instances);
  const KCamera& camera = s.device_scene.data().camera;
  p.merging = probe_merging_vertices(s.scene, embree, camera);
  const bool caustic_lit =
      m == VcmMode::vcm && s.scene.has_delta_surfaces() && p.merging.unlit > kMostlyUnlit;
  p.merges = s.settings.merges != Merges::automatic ? s.settings.merges
             : caustic_lit                          ? Merges::first
                                                    : Merges::caustic;
  p.caustic_lit = caustic_lit && p.merges == Merges::first;  // the counts go with all light merged
  p.seen = s.hooks.vcm_no_seen_light ? std::vector<int>(s.film.pixels(), 0)
                                     : seen_light_pixels(s.scene, embree, camera);
  return p;
}

}  // namespace kasha
