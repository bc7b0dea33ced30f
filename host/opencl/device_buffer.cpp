#include "opencl/device_buffer.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace kasha {

static std::string mib(double bytes) {
  char text[64];
  std::snprintf(text, sizeof text, "%.1f MiB", bytes / 1048576.0);
  return text;
}

cl::Buffer device_buffer(ClContext& cl, size_t bytes, const std::string& what, cl_mem_flags flags) {
  const DeviceInfo& d = cl.info();
  if (bytes > d.max_alloc_bytes || bytes > d.global_mem_bytes)
    throw Error(what + " need " + mib(static_cast<double>(bytes)) + ", more than " + d.name +
                " allocates in one buffer (" + mib(static_cast<double>(d.max_alloc_bytes)) + ")");
  try {
    return cl::Buffer(cl.context(), flags, std::max<size_t>(bytes, 1));
  } catch (const cl::Error& e) {
    throw Error(what + ": the device could not allocate " + mib(static_cast<double>(bytes)) + " (" +
                cl_error_text(e) + ")");
  }
}

size_t default_memory_budget(const DeviceInfo& d) {
  const bool cpu = d.type == "CPU";
  return static_cast<size_t>(
      std::min<unsigned long long>(d.max_alloc_bytes, d.global_mem_bytes / (cpu ? 8 : 4)));
}

}  // namespace kasha
