#pragma once
// A read-only device buffer holding a host vector. OpenCL rejects zero-sized buffers, so an empty
// vector gets one element that kernels never read.
#include <cstddef>
#include <vector>

#include "opencl/device.h"

namespace kasha {

// A read-only buffer with a copy of `bytes` (> 0) bytes. On a CPU device a large one lives in
// transparent huge pages: the traversal's random reads over a big BVH otherwise miss the TLB on
// most nodes (Embree's own BVH gets huge pages the same way).
cl::Buffer upload_bytes(ClContext& cl, const void* data, size_t bytes);

template <typename T>
cl::Buffer upload(ClContext& cl, const std::vector<T>& v) {
  std::vector<T> one(1);
  const std::vector<T>& data = v.empty() ? one : v;
  return upload_bytes(cl, data.data(), data.size() * sizeof(T));
}

}  // namespace kasha
