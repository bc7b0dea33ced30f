#pragma once
// A read-only device buffer holding a host vector, or several (tables) at aligned offsets. OpenCL
// rejects zero-sized buffers, so an empty vector gets one element that kernels never read.
#include <cstddef>
#include <cstdint>
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

// One host table of a packed upload, and where upload_tables writes its offset in the buffer.
struct HostTable {
  const void* data;
  size_t bytes;
  std::uint64_t* offset;
};

template <typename T>
HostTable host_table(const std::vector<T>& v, std::uint64_t& offset) {
  return {v.data(), v.size() * sizeof(T), &offset};
}

// One read-only buffer holding `tables` in order, each at a byte offset that is a multiple of
// kTableAlign (enough for any kernel type a pointer into it is cast to), written to its `offset`:
// kernels take one buffer and the offsets in place of a buffer per table. Huge pages as above.
constexpr size_t kTableAlign = 256;
cl::Buffer upload_tables(ClContext& cl, const std::vector<HostTable>& tables);

}  // namespace kasha
