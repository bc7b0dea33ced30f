#include "opencl/device.h"

#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/interrupt.h"

namespace kasha {

std::string cl_error_text(const cl::Error& e) {
  return std::string(e.what()) + " failed (OpenCL error " + std::to_string(e.err()) + ")";
}

void configure_kernel_cache() {
  if (std::getenv("POCL_CACHE_DIR")) return;
  std::error_code ec;
  std::filesystem::create_directories(KASHA_DEFAULT_KERNEL_CACHE, ec);
  if (!ec) setenv("POCL_CACHE_DIR", KASHA_DEFAULT_KERNEL_CACHE, 0);
}

static const char* kInstallAdvice =
    "no OpenCL device found: install an OpenCL driver, e.g. PoCL for the CPU "
    "(apt-get install pocl-opencl-icd, or run scripts/setup.sh)";

std::vector<DeviceInfo> list_devices() {
  configure_kernel_cache();
  SignalsBlockedInNewThreads compiler_threads_deaf;  // PoCL starts its worker threads here
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    throw Error(kInstallAdvice);  // the ICD loader reports "no platform" as an error
  }
  std::vector<DeviceInfo> out;
  for (cl::Platform& p : platforms) {
    std::vector<cl::Device> devices;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices
    }
    for (cl::Device& d : devices) {
      DeviceInfo info;
      info.index = static_cast<int>(out.size());
      info.platform = p.getInfo<CL_PLATFORM_NAME>();
      info.name = d.getInfo<CL_DEVICE_NAME>();
      info.version = d.getInfo<CL_DEVICE_VERSION>();
      info.driver = d.getInfo<CL_DRIVER_VERSION>();
      cl_device_type t = d.getInfo<CL_DEVICE_TYPE>();
      info.type = (t & CL_DEVICE_TYPE_GPU)   ? "GPU"
                  : (t & CL_DEVICE_TYPE_CPU) ? "CPU"
                                             : "accelerator";
      info.global_mem_bytes = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.max_alloc_bytes = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.device = d;
      out.push_back(info);
    }
  }
  if (out.empty()) throw Error(kInstallAdvice);
  return out;
}

ClContext::ClContext(int device_index) {
  std::vector<DeviceInfo> devices = list_devices();
  if (device_index < 0 || device_index >= static_cast<int>(devices.size()))
    throw Error("--device " + std::to_string(device_index) + ": no such OpenCL device (" +
                std::to_string(devices.size()) + " found; `kasha devices` lists them)");
  info_ = devices[device_index];
  SignalsBlockedInNewThreads compiler_threads_deaf;  // and a driver may start more for a context
  try {
    context_ = cl::Context(info_.device);
    queue_ = cl::CommandQueue(context_, info_.device);
  } catch (const cl::Error& e) {
    throw Error("OpenCL device " + std::to_string(device_index) + " (" + info_.name +
                "): " + cl_error_text(e));
  }
}

}  // namespace kasha
