#pragma once
// OpenCL device discovery and a context + queue on the chosen device.
#include <string>
#include <vector>

#include "opencl/cl.h"

namespace kasha {

struct DeviceInfo {
  int index = 0;  // kasha's flat index over all platforms, used by --device
  std::string platform, name, version, type;
  std::string driver;  // CL_DRIVER_VERSION
  unsigned long long global_mem_bytes = 0;
  unsigned long long max_alloc_bytes = 0;  // the largest single buffer
  unsigned compute_units = 0;
  cl::Device device;
};

// Every device of every platform. Throws kasha::Error with installation advice when there is none.
std::vector<DeviceInfo> list_devices();

// Points PoCL's kernel cache into the build tree (unless POCL_CACHE_DIR is already set), so reruns
// reuse compiled kernels; must run before the first OpenCL call.
void configure_kernel_cache();

class ClContext {
 public:
  explicit ClContext(int device_index = 0);
  const DeviceInfo& info() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  cl::Device& device() { return info_.device; }

 private:
  DeviceInfo info_;
  cl::Context context_;
  cl::CommandQueue queue_;
};

// "clGetPlatformIDs failed (-1001: CL_PLATFORM_NOT_FOUND_KHR)"
std::string cl_error_text(const cl::Error& e);

}  // namespace kasha
