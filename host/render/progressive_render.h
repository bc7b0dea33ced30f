#pragma once
// The progressive loop every integrator runs under: passes until --time or --passes, progress on
// the terminal (passes, elapsed, estimated remaining), an optional convergence log row after each
// pass, and Ctrl-C ending the loop after the pass in flight so the caller writes the image so far.
#include <optional>
#include <string>

#include "film/film.h"
#include "film/image.h"
#include "render/integrator.h"
#include "study/convergence_log.h"

namespace kasha {

struct StopCondition {
  double seconds = 0;  // > 0: stop once this much time has passed
  int passes = 0;      // > 0: stop after this many passes
};

struct RenderOptions {
  StopCondition stop;
  std::string log_path;            // convergence log CSV, or empty
  std::optional<Image> reference;  // for the log's error columns
  bool show_progress = true;
  bool keep_log = false;  // fill RenderSummary::log even without a log file
};

struct RenderSummary {
  int passes = 0;
  double seconds = 0;  // rendering time, without the log's error evaluation
  bool interrupted = false;
  std::vector<LogRow> log;  // when logging
};

// Stops early, after a whole pass, once interrupt_requested() (core/interrupt.h).
RenderSummary render_progressive(Integrator& integrator, Film& film, const RenderOptions& options);

}  // namespace kasha
