#pragma once
// One Embree device for the process, with errors turned into kasha::Error.
#include <embree3/rtcore.h>

namespace kasha {

RTCDevice embree_device();

}  // namespace kasha
