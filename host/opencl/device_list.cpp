#include "opencl/device_list.h"

#include <sstream>

#include "core/error.h"
#include "opencl/device.h"

namespace kasha {

std::vector<int> parse_device_list(const std::string& text) {
  const std::string where = "--device " + text;
  const int count = static_cast<int>(list_devices().size());
  std::vector<int> out;
  if (text == "all") {
    for (int i = 0; i < count; ++i) out.push_back(i);
    return out;
  }
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    if (item.empty() || item.size() > 6 || item.find_first_not_of("0123456789") != std::string::npos)
      throw Error(where + ": expected a device index, a comma-separated list of them, or all");
    const int index = std::stoi(item);
    if (index >= count)
      throw Error(where + ": no such OpenCL device " + item + " (" + std::to_string(count) +
                  " found; `kasha devices` lists them)");
    out.push_back(index);
  }
  if (out.empty() || text.back() == ',')
    throw Error(where + ": expected a device index, a comma-separated list of them, or all");
  if (out.size() > 64) throw Error(where + ": at most 64 devices");
  return out;
}

}  // namespace kasha
