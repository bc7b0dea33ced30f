#pragma once
// A read-only device buffer holding a host vector. OpenCL rejects zero-sized buffers, so an empty
// vector gets one element that kernels never read.
#include <vector>

#include "opencl/device.h"

namespace kasha {

template <typename T>
cl::Buffer upload(ClContext& cl, const std::vector<T>& v) {
  std::vector<T> one(1);
  const std::vector<T>& data = v.empty() ? one : v;
  return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, data.size() * sizeof(T),
                    const_cast<T*>(data.data()));
}

}  // namespace kasha
