#include "render/progressive_render.h"

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "core/interrupt.h"
#include "study/image_error.h"

namespace kasha {

RenderSummary render_progressive(Integrator& integrator, Film& film, const RenderOptions& options) {
  if (options.stop.seconds <= 0 && options.stop.passes <= 0)
    throw Error("give --time SECONDS or --passes N");
  using clock = std::chrono::steady_clock;
  RenderSummary summary;
  double shown_at = -1.0;
  for (int pass = 0;; ++pass) {
    // Only rendering counts towards the time: evaluating the error for the log does not.
    const auto pass_start = clock::now();
    film.accumulate(integrator.render_pass(pass));
    summary.passes = pass + 1;
    summary.seconds += std::chrono::duration<double>(clock::now() - pass_start).count();

    if (!options.log_path.empty() || options.keep_log) {
      LogRow row;
      row.integrator = integrator.name();
      row.pass = summary.passes;
      row.seconds = summary.seconds;
      row.camera_paths = integrator.camera_paths_per_pass() * summary.passes;
      row.photons = integrator.photons_per_pass() * summary.passes;
      if (options.reference) {
        ImageError e = image_error(film.image(), *options.reference);
        row.has_error = true;
        row.rmse = e.rmse;
        row.relmse = e.relmse;
      }
      summary.log.push_back(row);
    }

    bool done = (options.stop.passes > 0 && summary.passes >= options.stop.passes) ||
                (options.stop.seconds > 0 && summary.seconds >= options.stop.seconds);
    // A progress line at most four times a second, and always at the end.
    bool last = done || interrupt_requested();
    if (options.show_progress && (last || summary.seconds - shown_at >= 0.25)) {
      shown_at = summary.seconds;
      double per_pass = summary.seconds / summary.passes, left = 0;
      if (options.stop.passes > 0) left = per_pass * (options.stop.passes - summary.passes);
      if (options.stop.seconds > 0) left = std::max(0.0, options.stop.seconds - summary.seconds);
      std::fprintf(
          stderr, "\r%s: pass %d%s, %.1f s elapsed, ~%.1f s left   ", integrator.name().c_str(),
          summary.passes,
          options.stop.passes > 0 ? ("/" + std::to_string(options.stop.passes)).c_str() : "",
          summary.seconds, left);
      if (last) std::fprintf(stderr, "\n");
    }
    if (interrupt_requested()) {
      summary.interrupted = true;
      if (options.show_progress)
        std::fprintf(stderr, "interrupted: writing the image after %d passes\n", summary.passes);
      break;
    }
    if (done) break;
  }
  if (!options.log_path.empty()) write_convergence_log(options.log_path, summary.log);
  return summary;
}

}  // namespace kasha
