#include "opencl/upload.h"

#include <sys/mman.h>

#include <cstdlib>
#include <cstring>

namespace kasha {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

void CL_CALLBACK free_host_memory(cl_mem, void* memory) {
  std::free(memory);
}

}  // namespace

cl::Buffer upload_bytes(ClContext& cl, const void* data, size_t bytes) {
  if (cl.info().type == "CPU" && bytes >= 2 * kHugePage) {
    // The device uses host memory as given (CL_MEM_USE_HOST_PTR), freed when the buffer is.
    size_t size = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    if (void* memory = std::aligned_alloc(kHugePage, size)) {
      madvise(memory, size, MADV_HUGEPAGE);  // before the copy first touches the pages
      std::memcpy(memory, data, bytes);
      try {
        cl::Buffer buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, memory);
        buffer.setDestructorCallback(free_host_memory, memory);
        return buffer;
      } catch (const cl::Error&) {
        std::free(memory);  // the copying path below reports a real failure
      }
    }
  }
  return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                    const_cast<void*>(data));
}

}  // namespace kasha
