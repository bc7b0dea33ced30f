#include "render/progressive_render.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "render/image_error.h"

namespace kasha {

RenderSummary render_progressive(Integrator& integrator, Film& film, const RenderOptions& options) {
  if (options.stop.seconds <= 0 && options.stop.passes <= 0)
    throw Error("give --time SECONDS or --passes N");
  std::ostringstream log;
  log << "integrator,pass,seconds,camera_paths,photons,rmse,relmse\n";
  log << std::setprecision(9);

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  RenderSummary summary;
  double shown_at = -1.0;
  for (int pass = 0;; ++pass) {
    integrator.render_pass(pass, film);
    summary.passes = pass + 1;
    summary.seconds = std::chrono::duration<double>(clock::now() - start).count();

    if (!options.log_path.empty()) {
      log << integrator.name() << "," << summary.passes << "," << summary.seconds << ","
          << integrator.camera_paths_per_pass() * summary.passes << ","
          << integrator.photons_per_pass() * summary.passes << ",";
      if (options.reference) {
        ImageError e = image_error(film.image(), *options.reference);
        log << e.rmse << "," << e.relmse;
      } else {
        log << ",";
      }
      log << "\n";
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
  if (!options.log_path.empty())
    write_atomically(options.log_path, [&](const std::string& tmp) {
      std::ofstream out(tmp);
      out << log.str();
      if (!out) throw Error(options.log_path + ": write failed");
    });
  return summary;
}

}  // namespace kasha
