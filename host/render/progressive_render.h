#pragma once
// The progressive loop every integrator runs under: passes until --time or --passes, progress on
// the terminal (passes, elapsed, estimated remaining), an observer told of each pass (the
// convergence log), and Ctrl-C ending the loop after the pass in flight so the caller writes the
// image so far.
#include "film/film.h"
#include "render/integrator.h"
#include "render/pass_control.h"
#include "render/pass_observer.h"

namespace kasha {

struct RenderOptions {
  StopCondition stop;
  bool show_progress = true;
  PassObserver* observer = nullptr;  // told after each pass; its time does not count
};

struct RenderSummary {
  int passes = 0;
  double seconds = 0;  // rendering time, without the observer's
  bool interrupted = false;
};

// Seconds left of a render, counting the pass in flight (`in_flight_seconds` into it, `fraction`
// of it done, 0 when its integrator does not say): from that fraction where there is one, else
// from the `passes_done` passes before it; negative while nothing tells (the first pass, before
// it reports). What the progress line shows.
double seconds_left(const StopCondition& stop, int passes_done, double done_seconds,
                    double in_flight_seconds, double fraction);

// Stops early, after a whole pass, once interrupt_requested() (core/interrupt.h).
RenderSummary render_progressive(Integrator& integrator, Film& film, const RenderOptions& options);

}  // namespace kasha
