#pragma once
// Whole passes handed out to several devices (render/render_job.h): one thread per device takes
// the next pass as it comes free, so a faster device takes more; the progressive loop receives
// the results in pass order, and the film adds them in that order, so the image is the one a
// single device gives for the same seed and passes, bit for bit (film/pass_result.h).
#include <climits>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "render/integrator.h"

namespace kasha {

class PassScheduler : public Integrator {
 public:
  // One instance of the same integrator per device, each on its own device.
  explicit PassScheduler(std::vector<Integrator*> lanes);
  ~PassScheduler() override;
  PassScheduler(const PassScheduler&) = delete;
  PassScheduler& operator=(const PassScheduler&) = delete;

  // No pass from `passes` on is started (--passes); the default is no limit.
  void set_pass_limit(int passes) { limit_ = passes > 0 ? passes : INT_MAX; }
  // Pass `pass`, once the device that took it is done; devices take passes up to one each ahead.
  PassResult render_pass(int pass) override;

  long long camera_paths_per_pass() const override { return lanes_[0]->camera_paths_per_pass(); }
  long long photons_per_pass() const override { return lanes_[0]->photons_per_pass(); }
  std::map<std::string, size_t> device_buffers() const override {
    return lanes_[0]->device_buffers();
  }

 private:
  void run_lane(size_t lane);

  std::vector<Integrator*> lanes_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable changed_;
  int next_ = 0;     // the next pass a device takes
  int horizon_ = 0;  // passes below this may start
  int limit_ = INT_MAX;
  bool stopping_ = false;
  PassControl lane_control_;  // the deadline, without the progress display
  std::map<int, PassResult> done_;
  std::exception_ptr failure_;
};

}  // namespace kasha
