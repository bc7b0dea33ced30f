#pragma once
// Sizes kernel launches so that each takes about `target` seconds: the first launch of a kind is
// small, later ones follow the measured time per work item and grow at most fourfold, so a pass
// of any length checks its deadline and Ctrl-C a few times a second (render/pass_control.h).
#include <algorithm>
#include <chrono>
#include <cstddef>

namespace kasha {

class LaunchPacer {
 public:
  explicit LaunchPacer(double target_seconds = 0.2, size_t first = 256)
      : target_(target_seconds), next_(first) {}

  // How many work items the next launch should run, of `remaining`.
  size_t next(size_t remaining) const { return std::max<size_t>(1, std::min(remaining, next_)); }

  // A launch of `items` took `seconds`.
  void record(size_t items, double seconds) {
    if (items == 0) return;
    const double per_item = seconds / static_cast<double>(items);
    const double fit = per_item > 0 ? target_ / per_item : 4.0 * static_cast<double>(items);
    next_ = static_cast<size_t>(
        std::clamp(fit, 1.0, 4.0 * static_cast<double>(std::max(items, next_))));
  }

 private:
  double target_;
  size_t next_;
};

// Seconds since t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace kasha
