#pragma once
// `kasha converge`: error against run time for several integrators on one scene and device. Each
// integrator runs for the same rendering time (repeated with different seeds for error bars),
// logging after every pass against a reference (the analytic furnace, an EXR, or a cached
// reference render); the study writes the logs, a log–log plot, the final images side by side
// and a summary table.
#include <string>
#include <vector>

#include "render/integrator_registry.h"

namespace kasha {

struct StudyOptions {
  std::vector<std::string> integrators = IntegratorRegistry::names(true);  // the physical ones
  double seconds = 10;
  int passes = 0;  // > 0: every run stops after this many passes instead (tests)
  int repeats = 1;
  std::string reference;         // "furnace", an EXR, or empty: cached next to the scene
  double reference_seconds = 0;  // for a new cached reference; <= 0: 4 × seconds × integrators
  double target = -1;            // RMSE for time-to-target; < 0: the worst final RMSE
  std::string out_dir;
  IntegratorSettings settings;
  std::string device = "0";  // --device: an index, a list or all
  bool show_progress = true;
  bool plot = true;  // run scripts/plot_convergence.py (matplotlib)
};

struct IntegratorSummary {
  std::string integrator;
  int runs = 0;
  double final_rmse = 0, final_rmse_sd = 0, final_relmse = 0, final_relmse_sd = 0;
  double slope_rmse = 0, slope_rmse_sd = 0, slope_relmse = 0, slope_relmse_sd = 0;
  double time_to_target = -1;  // mean over runs that reached it; -1 if none did
  int reached_target = 0;
  double camera_paths_per_second = 0, photons_per_second = 0;
  double startup = 0;  // seconds of one-time start-up in the first pass (kernel JIT), mean
};

struct StudyResult {
  std::string reference_description;
  double target = 0;
  std::vector<IntegratorSummary> summaries;
};

// Checks arguments (integrator names, a reference that exists or can be made, a writable
// directory) before any rendering; throws kasha::Error with one clear line.
StudyResult run_convergence_study(const std::string& scene_path, const StudyOptions& options);

// Where the slope fit starts: the first twentieth of the budget is left out (photon mapping's
// initial radius); the first pass's one-time start-up is taken off the times before fitting.
constexpr double kSlopeFitFrom = 0.05;

}  // namespace kasha
