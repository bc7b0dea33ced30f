#pragma once
// What one pass computes, kept apart from accumulating it into the film: sums that add up over
// passes in a fixed order, so that passes computed elsewhere (other devices, other processes) give
// the same image once accumulated.
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace kasha {

// An image an integrator keeps on the device (photon mapping's SPPM statistics), read when the
// image is wanted rather than every pass: pixels × rows, radiance per nm. Valid while the
// integrator that handed it out lives.
using KeptImage = std::function<std::vector<float>()>;

// Tallies of what the path-depth guard (KASHA_MAX_PATH_DEPTH) cut: the weight or power it cut,
// and of how much; `render` warns when their ratio exceeds 1e-4 (the image is biased low).
constexpr const char* kDepthGuardCut = "depth guard: cut";
constexpr const char* kDepthGuardOf = "depth guard: of";
// The same for photon mapping's camera paths, apart from its photons'.
constexpr const char* kCameraDepthGuardCut = "depth guard: camera paths cut";
constexpr const char* kCameraDepthGuardOf = "depth guard: camera paths of";

// The work each device did when a render runs on several ("device 1: work"): passes, or for
// photon mapping the photons traced; `render` shows each device's share.
inline std::string device_work_tally(size_t device) {
  return "device " + std::to_string(device) + ": work";
}

// Rays the pass's kernels traced (every bvh_closest and bvh_occluded query; kasha bench's rays/s).
constexpr const char* kClosestRays = "rays: closest";
constexpr const char* kShadowRays = "rays: shadow";
// Photon mapping: visible points' queries of the photon store (a pixel's per gather of the store).
constexpr const char* kGatherQueries = "gather queries";

struct PassResult {
  int pass = 0;
  long long samples = 0;  // samples per pixel that `sums` adds up
  // When a pass was cut short (deadline, Ctrl-C) after some pixels' samples: each pixel's own
  // count, which `samples` then is the least of; empty when every pixel has `samples`.
  std::vector<long long> pixel_samples;
  std::vector<double> sums;  // pixels × film rows
  double fraction = 1;       // of the pass's work done: < 1 when it was cut short
  KeptImage kept;  // if set: the integrator's image so far, added to the sums' mean
  // Counters that add over passes: "rejected samples", power and time figures, by name.
  std::map<std::string, double> tallies;
};

}  // namespace kasha
