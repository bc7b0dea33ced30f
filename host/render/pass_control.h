#pragma once
// What bounds the pass in flight: a deadline (from --time) and Ctrl-C, checked between kernel
// launches so that a long pass ends early with the work done so far, and a progress report after
// each launch. Integrators split their passes into launches of bounded work
// (render/launch_pacer.h).
#include <chrono>
#include <functional>
#include <optional>

#include "core/interrupt.h"

namespace kasha {

// When a render stops: at whichever of its time and its passes comes first.
struct StopCondition {
  double seconds = 0;  // > 0: stop once this much time has passed
  int passes = 0;      // > 0: stop after this many passes
  bool given() const { return seconds > 0 || passes > 0; }
};

struct PassControl {
  using Clock = std::chrono::steady_clock;
  std::optional<Clock::time_point> deadline;
  std::function<void(double fraction)> progress;  // of the pass done, after each launch

  bool stop_now() const { return interrupt_requested() || (deadline && Clock::now() >= *deadline); }
  void report(double fraction) const {
    if (progress) progress(fraction);
  }
};

}  // namespace kasha
