#pragma once
// What a pass counted besides its image, as named fields (pbrt-v4's STAT_COUNTER is the model): a
// counter misspelled does not compile, rather than reading 0. The film adds every pass's counters
// with PassCounters::add, in pass order; each field says how it combines.
#include <string>
#include <vector>

namespace kasha {

// What the path-depth guard (KASHA_MAX_PATH_DEPTH) cut: the weight or power it cut, and of how
// much; `render` warns when their ratio exceeds 1e-4 (the image is biased low).
struct DepthGuardTally {
  double cut = 0;  // adds
  double of = 0;   // adds
};

// Seconds an integrator spent in one of its stages; `render` shows each stage's share.
struct StageTime {
  std::string stage;
  double seconds = 0;
};

struct PassCounters {
  double rejected_samples = 0;  // adds: samples that were not finite and were left out
  // Forward: the photons' power, adding over passes (absorbed + escaped + in flight = emitted).
  double power_emitted_w = 0, power_absorbed_w = 0, power_escaped_w = 0, power_in_flight_w = 0;
  DepthGuardTally depth_guard;         // adds: paths, or photons (per photon's start)
  DepthGuardTally camera_depth_guard;  // adds: photon mapping's and vcm's camera paths
  // Adds: rays the pass's kernels traced (every bvh_closest and bvh_occluded query; kasha bench's
  // rays/s).
  double closest_rays = 0, shadow_rays = 0;
  // Adds: photon mapping's visible points' queries of the photon store (a pixel's per gather).
  double gather_queries = 0;
  double photons_stored = 0;          // adds: photon mapping's store records
  double photon_store_overflows = 0;  // adds: photon ranges traced again in halves
  double light_vertices_stored = 0;   // adds: vcm
  double light_chunks = 0;            // adds: vcm
  // Vcm's typical merging radius of the pass. Adds like the rest (nothing reads it): the film's
  // is the sum over passes, their mean times the passes.
  double merging_radius = 0;
  // The work each device did when a render runs on several, by device index: passes (the pass's
  // fraction done), or for photon mapping the photons traced. Adds per device over passes; a
  // device missing from a pass counts 0.
  std::vector<double> device_work;
  // Stages timed, in order of stage name (the order `render` prints them in), each once. Adds per
  // stage over passes; a stage missing from a pass counts 0.
  std::vector<StageTime> stage_seconds;

  // The counters of one more pass, added as each field says.
  PassCounters& add(const PassCounters& pass);
  // Adds `seconds` to `stage`, entered in name order if it is new.
  void add_stage(const std::string& stage, double seconds);
  // Sets a device's work, entering devices up to it with none.
  void set_device_work(size_t device, double work);
  double work_of(size_t device) const {
    return device < device_work.size() ? device_work[device] : 0.0;
  }
};

}  // namespace kasha
