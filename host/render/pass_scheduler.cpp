#include "render/pass_scheduler.h"

#include <algorithm>
#include <chrono>

namespace kasha {

PassScheduler::PassScheduler(std::vector<Integrator*> lanes) : lanes_(std::move(lanes)) {
  rename(lanes_.at(0)->name());
}

PassScheduler::~PassScheduler() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (std::thread& t : threads_) t.join();
}

PassResult PassScheduler::render_pass(int pass) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (threads_.empty())
    for (size_t lane = 0; lane < lanes_.size(); ++lane)
      threads_.emplace_back([this, lane] { run_lane(lane); });
  lane_control_ = control_;
  lane_control_.progress = nullptr;  // shown from this thread only
  next_ = std::max(next_, pass);
  horizon_ = static_cast<int>(std::min<long long>(limit_, pass + static_cast<long long>(lanes_.size())));
  changed_.notify_all();
  // Wake now and then to show progress while the devices work.
  while (!done_.count(pass) && !failure_) {
    changed_.wait_for(lock, std::chrono::milliseconds(250));
    lock.unlock();
    control_.report(0);
    lock.lock();
  }
  if (failure_) std::rethrow_exception(failure_);
  PassResult r = std::move(done_.at(pass));
  done_.erase(pass);
  return r;
}

void PassScheduler::run_lane(size_t index) {
  Integrator& lane = *lanes_[index];
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || failure_ || next_ < horizon_; });
    if (stopping_ || failure_) return;
    const int pass = next_++;
    lane.set_control(lane_control_);
    lock.unlock();
    try {
      PassResult r = lane.render_pass(pass);
      r.tallies[device_work_tally(index)] = r.fraction;
      lock.lock();
      done_[pass] = std::move(r);
    } catch (...) {
      lock.lock();
      if (!failure_) failure_ = std::current_exception();
    }
    changed_.notify_all();
  }
}

}  // namespace kasha
