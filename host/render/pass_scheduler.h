#pragma once
// Whole passes handed out to several devices (render/render_job.h) through the ordered work
// distributor (render/ordered_work.h): each device takes the next pass as it comes free, at most
// one pass ahead each; the progressive loop receives the results in pass order, and the film adds
// them in that order, so the image is the one a single device gives for the same seed and passes,
// bit for bit (film/pass_result.h).
#include <climits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "render/integrator.h"
#include "render/ordered_work.h"

namespace kasha {

class PassScheduler : public Integrator {
 public:
  // One instance of the same integrator per device, each on its own device.
  explicit PassScheduler(std::vector<Integrator*> lanes);

  // No pass from `passes` on is started (--passes); the default is no limit.
  void set_pass_limit(int passes) { limit_ = passes > 0 ? passes : INT_MAX; }
  // Pass `pass`, once the device that took it is done; its progress is the one shown meanwhile.
  PassResult render_pass(int pass) override;

  long long camera_paths_per_pass() const override { return lanes_[0]->camera_paths_per_pass(); }
  long long photons_per_pass() const override { return lanes_[0]->photons_per_pass(); }
  std::map<std::string, size_t> device_buffers() const override {
    return lanes_[0]->device_buffers();
  }

 private:
  PassResult run_lane(size_t lane, int pass);

  std::vector<Integrator*> lanes_;
  int limit_ = INT_MAX;
  std::mutex mutex_;                // guards the two below
  PassControl lane_control_;        // the deadline, without the progress display
  std::map<int, double> fraction_;  // of the passes in flight, as their devices report it
  std::unique_ptr<OrderedWork<PassResult>> work_;  // last: its threads use the members above
};

}  // namespace kasha
