#include "opencl/upload.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>

namespace kasha {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

void CL_CALLBACK free_host_memory(cl_mem, void* memory) {
  std::free(memory);
}

// A CPU device's large read-only buffer in transparent huge pages: the traversal's random reads
// over a big BVH otherwise miss the TLB on most nodes. `fill` writes its contents; an empty
// buffer where this does not apply or fails (the caller's ordinary path reports a real failure).
cl::Buffer huge_page_buffer(ClContext& cl, size_t bytes,
                            const std::function<void(unsigned char*)>& fill) {
  if (cl.info().type != "CPU" || bytes < 2 * kHugePage) return cl::Buffer();
  // The device uses host memory as given (CL_MEM_USE_HOST_PTR), freed when the buffer is.
  size_t size = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* memory = std::aligned_alloc(kHugePage, size);
  if (!memory) return cl::Buffer();
  madvise(memory, size, MADV_HUGEPAGE);  // before the copy first touches the pages
  fill(static_cast<unsigned char*>(memory));
  try {
    cl::Buffer buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, memory);
    buffer.setDestructorCallback(free_host_memory, memory);
    return buffer;
  } catch (const cl::Error&) {
    std::free(memory);
    return cl::Buffer();
  }
}

}  // namespace

cl::Buffer upload_bytes(ClContext& cl, const void* data, size_t bytes) {
  cl::Buffer huge =
      huge_page_buffer(cl, bytes, [&](unsigned char* to) { std::memcpy(to, data, bytes); });
  if (huge()) return huge;
  return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                    const_cast<void*>(data));
}

cl::Buffer upload_tables(ClContext& cl, const std::vector<HostTable>& tables) {
  size_t end = 0;
  for (const HostTable& t : tables) {
    end = (end + kTableAlign - 1) / kTableAlign * kTableAlign;
    *t.offset = end;
    end += t.bytes;
  }
  const size_t bytes = std::max<size_t>(end, 1);
  cl::Buffer huge = huge_page_buffer(cl, bytes, [&](unsigned char* to) {
    size_t filled = 0;  // the padding is zeroed, so no byte of the buffer is left unset
    for (const HostTable& t : tables) {
      std::memset(to + filled, 0, *t.offset - filled);
      if (t.bytes) std::memcpy(to + *t.offset, t.data, t.bytes);
      filled = *t.offset + t.bytes;
    }
  });
  if (huge()) return huge;
  // Written table by table, so the host holds no second copy of the scene.
  cl::Buffer buffer(cl.context(), CL_MEM_READ_ONLY, bytes);
  for (const HostTable& t : tables)
    if (t.bytes) cl.queue().enqueueWriteBuffer(buffer, CL_TRUE, *t.offset, t.bytes, t.data);
  return buffer;
}

}  // namespace kasha
