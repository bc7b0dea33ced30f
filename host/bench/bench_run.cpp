#include "bench/bench_run.h"

#include <chrono>

#include "core/error.h"
#include "core/peak_memory.h"
#include "render/render_job.h"
#include "study/convergence_log.h"

namespace kasha {

double BenchRun::per_second(double count) const {
  const double steady = seconds - startup_seconds;
  return steady > 0 ? count / steady : 0;
}

BenchRun bench_on_devices(const LoadedBenchScene& s, const std::string& integrator,
                          const std::vector<BenchDevice>& devices, double seconds,
                          bool show_progress) {
  if (devices.empty()) throw Error("bench: no device");
  BenchRun run;
  run.scene = s.bench->name;
  run.integrator = integrator;
  std::vector<RenderLane> lanes;
  for (const BenchDevice& d : devices) {
    run.devices.push_back(d.cl.info().index);
    lanes.push_back({d.cl, d.scene});
  }
  run.width = s.scene.camera.width;
  run.height = s.scene.camera.height;

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  IntegratorSettings settings;  // every integrator's defaults, seed 1
  {
    // Untimed warm-up, a pass a device: PoCL compiles a kernel's work-group function at its first launch (seconds
    // on a cold cache, more on a loaded machine). One pass of a throwaway job puts every kernel
    // the run launches in PoCL's cache, so the timed run renders rather than compiles; else a slow
    // build leaves vcm or bpt, whose first iteration is never cut, one iteration: too noisy to
    // validate.
    RenderJob warm_up(lanes, s.scene, integrator, settings, false);
    RenderOptions one;
    one.stop.passes = static_cast<int>(lanes.size());  // one a device
    one.show_progress = false;
    warm_up.run(one);
  }
  reset_peak_resident_memory();
  RenderJob job(lanes, s.scene, integrator, settings, false);
  run.kernel_build_seconds = std::chrono::duration<double>(clock::now() - t0).count();

  RenderOptions options;
  options.stop.seconds = seconds;
  options.show_progress = show_progress;
  ConvergenceLog log;  // rows without errors: the start-up comes from their times
  options.observer = &log;
  RenderSummary summary = job.run(options);
  const Film& film = job.film();
  Integrator& in = job.integrator();
  run.seconds = summary.seconds;
  run.passes = summary.passes;
  run.interrupted = summary.interrupted;
  run.samples_per_pixel = film.samples_per_pixel();
  run.startup_seconds = startup_seconds(log.rows());
  run.camera_paths = static_cast<double>(in.camera_paths_per_pass()) * film.work_passes();
  run.photons = static_cast<double>(in.photons_per_pass()) * film.work_passes();
  run.closest_rays = film.counters().closest_rays;
  run.shadow_rays = film.counters().shadow_rays;
  run.gather_queries = film.counters().gather_queries;
  // Device time and memory add over the devices (launches overlap in time across devices).
  for (size_t d = 0; d < job.local_devices(); ++d) {
    Integrator& lane = job.integrator(d);
    run.device_seconds += lane.device_seconds();
    run.device_memory_bytes += devices[d].scene.data().bytes() + job.device_film(d).table_bytes();
    for (const auto& [what, bytes] : lane.device_buffers()) run.device_memory_bytes += bytes;
  }
  run.host_seconds = std::max(0.0, run.seconds - run.device_seconds / job.local_devices());
  run.build_options = in.build_options();
  run.validation = validate_image(film.image(), s.reference, s.bench->bound);
  run.host_memory_bytes = peak_resident_memory_bytes();
  return run;
}

}  // namespace kasha
