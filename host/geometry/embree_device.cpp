#include "geometry/embree_device.h"

#include <string>

#include "core/error.h"

namespace kasha {

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d)
      throw Error("Embree: cannot create a device (error " +
                  std::to_string(rtcGetDeviceError(nullptr)) + ")");
    return d;
  }();
  return device;
}

}  // namespace kasha
