#pragma once
// A read-write device buffer whose size is checked against the device's limits first, so that a
// scene or setting too large for the device gets one clear line instead of OpenCL error -61.
#include <string>

#include "opencl/device.h"

namespace kasha {

// `what` names the buffer and the setting that sizes it, e.g. "photon: the visible points".
cl::Buffer device_buffer(ClContext& cl, size_t bytes, const std::string& what,
                         cl_mem_flags flags = CL_MEM_READ_WRITE);

// The bytes a memory budget may take on this device when none is given: a quarter of the
// device's global memory (an eighth on a CPU device, whose memory the host's copies share), and
// no more than one buffer may hold.
size_t default_memory_budget(const DeviceInfo& device);

}  // namespace kasha
