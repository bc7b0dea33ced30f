#include "render/pass_scheduler.h"

#include <algorithm>

namespace kasha {

PassScheduler::PassScheduler(std::vector<Integrator*> lanes) : lanes_(std::move(lanes)) {
  rename(lanes_.at(0)->name());
  work_ = std::make_unique<OrderedWork<PassResult>>(
      lanes_.size(),
      [this](size_t lane, long long pass) { return run_lane(lane, static_cast<int>(pass)); });
}

PassResult PassScheduler::render_pass(int pass) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    lane_control_ = control_;
    lane_control_.progress = nullptr;  // shown from this thread only
  }
  work_->allow_until(std::min<long long>(limit_, pass + static_cast<long long>(lanes_.size())));
  PassResult r = work_->take(pass, [&] {
    double fraction = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (fraction_.count(pass)) fraction = fraction_[pass];
    }
    control_.report(fraction);
  });
  std::lock_guard<std::mutex> lock(mutex_);
  fraction_.erase(pass);
  return r;
}

PassResult PassScheduler::run_lane(size_t index, int pass) {
  Integrator& lane = *lanes_[index];
  PassControl control;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    control = lane_control_;
  }
  control.progress = [this, pass](double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    fraction_[pass] = fraction;
  };
  lane.set_control(control);
  PassResult r = lane.render_pass(pass);
  r.counters.set_device_work(index, r.fraction);
  return r;
}

}  // namespace kasha
