#pragma once
// One bench run: a scene rendered by one integrator for a fixed time on a set of devices, what it
// measured (throughput, rays, time, memory) and whether its image is right.
#include <string>
#include <vector>

#include "bench/bench_reference.h"
#include "bench/bench_validation.h"
#include "opencl/device.h"
#include "render/device_scene.h"

namespace kasha {

struct BenchRun {
  std::string scene, integrator;
  std::vector<int> devices;  // kasha's device indices (`kasha devices`)
  int width = 0, height = 0;
  double seconds = 0;  // rendering: the progressive loop's time
  int passes = 0;
  long long samples_per_pixel = 0;
  // Making the render job: building the integrator's kernels (from PoCL's cache when it is warm)
  // and allocating its buffers; apart from `seconds`.
  double kernel_build_seconds = 0;
  // The first pass's one-time excess over the median pass (a device compiling a kernel at its
  // first launch), within `seconds`; rates leave it out.
  double startup_seconds = 0;
  double camera_paths = 0, photons = 0, closest_rays = 0, shadow_rays = 0, gather_queries = 0;
  double device_seconds = 0;       // the integrator's launches, enqueue to finish
  double host_seconds = 0;         // the rest of `seconds`
  size_t device_memory_bytes = 0;  // the scene, the film's tables and the integrator's buffers
  size_t host_memory_bytes = 0;    // peak resident memory during the run
  std::string build_options;
  Validation validation;
  bool interrupted = false;

  // Per second of steady rendering: `seconds` less the first launch's start-up.
  double per_second(double count) const;
  double samples() const { return camera_paths + photons; }  // what the score counts
  bool valid() const { return validation.valid && !interrupted; }
};

// A device of a run's device set: its context and the scene uploaded to it.
struct BenchDevice {
  ClContext& cl;
  DeviceScene& scene;
};

// The one place a run is made: `integrator` renders `s` for `seconds` on `devices`, and the image
// is validated against the scene's reference. Today a device set holds one device (each listed
// device is benchmarked in turn); rendering one image on several devices replaces this body.
// Stops after the pass in flight on Ctrl-C (the run is then marked interrupted).
BenchRun bench_on_devices(const LoadedBenchScene& s, const std::string& integrator,
                          const std::vector<BenchDevice>& devices, double seconds,
                          bool show_progress);

}  // namespace kasha
