#pragma once
// Work items 0, 1, 2, … handed out in order to whichever lane comes free — one thread a lane, so
// a faster device takes more (LuxCore's one render thread per device) — and their results taken
// back in item order, so whatever is built from them in that order does not depend on which lane
// did which item, or when: the image on several devices is the one device's, bit for bit. Whole
// passes (render/pass_scheduler.h) and the chunks of photon mapping's shared passes
// (integrators/photon/photon_pass_chunks.h) go through it, to local devices and to other MPI ranks
// (mpi/remote_lane.h) alike.
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace kasha {

template <typename Result>
class OrderedWork {
 public:
  // `work(lane, item)` runs on lane `lane`'s own thread. No item starts before allow_until.
  OrderedWork(size_t lanes, std::function<Result(size_t lane, long long item)> work)
      : work_(std::move(work)) {
    for (size_t lane = 0; lane < lanes; ++lane) threads_.emplace_back([this, lane] { run(lane); });
  }
  // Lets the items in flight finish; starts no more.
  ~OrderedWork() {
    stop();
    for (std::thread& t : threads_) t.join();
  }
  OrderedWork(const OrderedWork&) = delete;
  OrderedWork& operator=(const OrderedWork&) = delete;

  // Items below `end` may start.
  void allow_until(long long end) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      end_ = std::max(end_, end);
    }
    changed_.notify_all();
  }

  // No more items start.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
  }

  // The result of `item`, once its lane is done with it; `waiting` is called every 250 ms until
  // then (to show progress). Rethrows the first failure of any item, and no item starts after one.
  Result take(long long item, const std::function<void()>& waiting = nullptr) {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_.count(item) && !failure_) {
      changed_.wait_for(lock, std::chrono::milliseconds(250));
      if (waiting && !done_.count(item) && !failure_) {
        lock.unlock();
        waiting();
        lock.lock();
      }
    }
    if (failure_) std::rethrow_exception(failure_);
    Result r = std::move(done_.at(item));
    done_.erase(item);
    return r;
  }

 private:
  void run(size_t lane) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [&] { return stopping_ || failure_ || next_ < end_; });
      if (stopping_ || failure_) return;
      const long long item = next_++;
      lock.unlock();
      try {
        Result r = work_(lane, item);
        lock.lock();
        done_.emplace(item, std::move(r));
      } catch (...) {
        lock.lock();
        if (!failure_) failure_ = std::current_exception();
      }
      changed_.notify_all();
    }
  }

  std::function<Result(size_t, long long)> work_;
  std::mutex mutex_;
  std::condition_variable changed_;
  long long next_ = 0, end_ = 0;  // the next item a lane takes; items below end_ may start
  bool stopping_ = false;
  std::map<long long, Result> done_;
  std::exception_ptr failure_;
  std::vector<std::thread> threads_;  // last: its threads see the members above made
};

}  // namespace kasha
