#include "render/progressive_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/interrupt.h"

namespace kasha {

double seconds_left(const StopCondition& stop, int passes_done, double done_seconds,
                    double in_flight_seconds, double fraction) {
  double left = -1;
  if (stop.passes > 0) {
    const double elapsed = done_seconds + in_flight_seconds;
    if (fraction > 0) {
      left = elapsed / (passes_done + fraction) * (stop.passes - passes_done - fraction);
    } else if (passes_done > 0) {
      const double per_pass = done_seconds / passes_done;
      const int after_this = stop.passes - passes_done - 1;
      left = std::max(per_pass * after_this, per_pass * (after_this + 1) - in_flight_seconds);
    }
  }
  if (stop.seconds > 0) {
    const double by_time = std::max(0.0, stop.seconds - done_seconds - in_flight_seconds);
    left = left < 0 ? by_time : std::min(left, by_time);
  }
  return left;
}


RenderSummary render_progressive(Integrator& integrator, Film& film, const RenderOptions& options) {
  if (!options.stop.given()) throw std::logic_error("render_progressive: no stop condition");
  using clock = std::chrono::steady_clock;
  RenderSummary summary;
  double shown_at = -1.0;
  // The progress line: `in_flight` seconds into the pass after summary.passes, `fraction` of it
  // done (0: not reported); `last` ends the line.
  auto show = [&](double in_flight, double fraction, bool last) {
    const double seconds = summary.seconds + in_flight;
    if (!options.show_progress || (!last && seconds - shown_at < 0.25)) return;
    shown_at = seconds;
    std::string pass = std::to_string(summary.passes + (last ? 0 : 1));
    if (options.stop.passes > 0) pass += "/" + std::to_string(options.stop.passes);
    if (!last && fraction > 0)
      pass += " (" + std::to_string(static_cast<int>(100 * fraction)) + " %)";
    const double left =
        last ? 0 : seconds_left(options.stop, summary.passes, summary.seconds, in_flight, fraction);
    char left_text[64] = "estimating time left";
    if (left >= 0) std::snprintf(left_text, sizeof left_text, "~%.1f s left", left);
    std::fprintf(stderr, "\r%s: pass %s, %.1f s elapsed, %s   ", integrator.name().c_str(),
                 pass.c_str(), seconds, left_text);
    if (last) std::fprintf(stderr, "\n");
  };
  for (int pass = 0;; ++pass) {
    // Only rendering counts towards the time: what the observer does after a pass does not. The
    // deadline reaches into the pass: its launches stop there (render/pass_control.h).
    const auto pass_start = clock::now();
    PassControl control;
    if (options.stop.seconds > 0)
      control.deadline =
          pass_start + std::chrono::duration_cast<clock::duration>(
                           std::chrono::duration<double>(options.stop.seconds - summary.seconds));
    control.progress = [&](double fraction) {
      show(std::chrono::duration<double>(clock::now() - pass_start).count(), fraction, false);
    };
    integrator.set_control(control);
    PassResult result = integrator.render_pass(pass);
    const bool cut_short = result.fraction < 1;
    film.accumulate(result);
    summary.passes = pass + 1;
    summary.seconds += std::chrono::duration<double>(clock::now() - pass_start).count();

    if (options.observer) {
      PassRecord record;
      record.integrator = integrator.name();
      record.pass = summary.passes;
      record.seconds = summary.seconds;
      record.camera_paths =
          static_cast<long long>(integrator.camera_paths_per_pass() * film.work_passes());
      record.photons = static_cast<long long>(integrator.photons_per_pass() * film.work_passes());
      options.observer->pass_done(record, film);
    }

    bool done = cut_short || (options.stop.passes > 0 && summary.passes >= options.stop.passes) ||
                (options.stop.seconds > 0 && summary.seconds >= options.stop.seconds);
    show(0, 0, done || interrupt_requested());
    if (interrupt_requested()) {
      summary.interrupted = true;
      if (options.show_progress)
        std::fprintf(stderr, "interrupted: writing the image after %d passes\n", summary.passes);
      break;
    }
    if (done) break;
  }
  return summary;
}

}  // namespace kasha
