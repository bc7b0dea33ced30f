#pragma once
// Host work spread over the machine's hardware threads by oneTBB (work stealing, so unevenly
// loaded ranges such as the gather balance out; an exception in a worker reaches the caller).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace kasha {

// Calls work(begin, end) on disjoint ranges covering [0, count).
template <typename Work>
void parallel_for(size_t count, const Work& work) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64),
                    [&](const tbb::blocked_range<size_t>& r) { work(r.begin(), r.end()); });
}

}  // namespace kasha
