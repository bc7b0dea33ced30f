#include "film/pass_counters.h"

#include <algorithm>

namespace kasha {

PassCounters& PassCounters::add(const PassCounters& pass) {
  rejected_samples += pass.rejected_samples;
  power_emitted_w += pass.power_emitted_w;
  power_absorbed_w += pass.power_absorbed_w;
  power_escaped_w += pass.power_escaped_w;
  power_in_flight_w += pass.power_in_flight_w;
  depth_guard.cut += pass.depth_guard.cut;
  depth_guard.of += pass.depth_guard.of;
  camera_depth_guard.cut += pass.camera_depth_guard.cut;
  camera_depth_guard.of += pass.camera_depth_guard.of;
  closest_rays += pass.closest_rays;
  shadow_rays += pass.shadow_rays;
  gather_queries += pass.gather_queries;
  photons_stored += pass.photons_stored;
  photon_store_overflows += pass.photon_store_overflows;
  light_vertices_stored += pass.light_vertices_stored;
  light_chunks += pass.light_chunks;
  merging_radius += pass.merging_radius;
  if (device_work.size() < pass.device_work.size()) device_work.resize(pass.device_work.size());
  for (size_t d = 0; d < pass.device_work.size(); ++d) device_work[d] += pass.device_work[d];
  for (const StageTime& s : pass.stage_seconds) add_stage(s.stage, s.seconds);
  return *this;
}

void PassCounters::add_stage(const std::string& stage, double seconds) {
  auto at =
      std::lower_bound(stage_seconds.begin(), stage_seconds.end(), stage,
                       [](const StageTime& s, const std::string& name) { return s.stage < name; });
  if (at != stage_seconds.end() && at->stage == stage)
    at->seconds += seconds;
  else
    stage_seconds.insert(at, StageTime{stage, seconds});
}

void PassCounters::set_device_work(size_t device, double work) {
  if (device_work.size() <= device) device_work.resize(device + 1, 0.0);
  device_work[device] = work;
}

}  // namespace kasha
