#include "render/progressive_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

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
  auto show = [&](double seconds, double pass_fraction, bool last) {
    if (!options.show_progress || (!last && seconds - shown_at < 0.25)) return;
    shown_at = seconds;
    const double passes = summary.passes + pass_fraction;
    double left = 0;
    if (options.stop.passes > 0 && passes > 0)
      left = seconds / passes * (options.stop.passes - passes);
    if (options.stop.seconds > 0) left = std::max(0.0, options.stop.seconds - seconds);
    std::string pass = std::to_string(summary.passes + (last ? 0 : 1));
    if (options.stop.passes > 0) pass += "/" + std::to_string(options.stop.passes);
    if (!last && pass_fraction > 0)
      pass += " (" + std::to_string(static_cast<int>(100 * pass_fraction)) + " %)";
    std::fprintf(stderr, "\r%s: pass %s, %.1f s elapsed, ~%.1f s left   ",
                 integrator.name().c_str(), pass.c_str(), seconds, left);
    if (last) std::fprintf(stderr, "\n");
  };
  for (int pass = 0;; ++pass) {
    // Only rendering counts towards the time: evaluating the error for the log does not. The
    // deadline reaches into the pass: its launches stop there (render/pass_control.h).
    const auto pass_start = clock::now();
    PassControl control;
    if (options.stop.seconds > 0)
      control.deadline =
          pass_start + std::chrono::duration_cast<clock::duration>(
                           std::chrono::duration<double>(options.stop.seconds - summary.seconds));
    const double before = summary.seconds;
    control.progress = [&](double fraction) {
      show(before + std::chrono::duration<double>(clock::now() - pass_start).count(), fraction,
           false);
    };
    integrator.set_control(control);
    PassResult result = integrator.render_pass(pass);
    const bool cut_short = result.fraction < 1;
    film.accumulate(result);
    summary.passes = pass + 1;
    summary.seconds += std::chrono::duration<double>(clock::now() - pass_start).count();

    if (!options.log_path.empty() || options.keep_log) {
      LogRow row;
      row.integrator = integrator.name();
      row.pass = summary.passes;
      row.seconds = summary.seconds;
      row.camera_paths =
          static_cast<long long>(integrator.camera_paths_per_pass() * film.work_passes());
      row.photons = static_cast<long long>(integrator.photons_per_pass() * film.work_passes());
      if (options.reference) {
        ImageError e = image_error(film.image(), *options.reference);
        row.has_error = true;
        row.rmse = e.rmse;
        row.relmse = e.relmse;
      }
      summary.log.push_back(row);
    }

    bool done = cut_short || (options.stop.passes > 0 && summary.passes >= options.stop.passes) ||
                (options.stop.seconds > 0 && summary.seconds >= options.stop.seconds);
    show(summary.seconds, 0, done || interrupt_requested());
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
