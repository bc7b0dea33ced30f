#pragma once
// Host work spread over the machine's hardware threads in contiguous chunks (the gather, the
// disc-coverage probes, Embree's reference intersections).
#include <algorithm>
#include <functional>
#include <thread>
#include <vector>

namespace kasha {

// Calls work(begin, end) on disjoint ranges covering [0, count), one per hardware thread.
inline void parallel_for(size_t count, const std::function<void(size_t, size_t)>& work) {
  const size_t threads = std::max(1u, std::thread::hardware_concurrency());
  const size_t chunk = (count + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back(work, std::min(count, t * chunk), std::min(count, (t + 1) * chunk));
  for (auto& th : pool) th.join();
}

}  // namespace kasha
