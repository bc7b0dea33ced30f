#include "opencl/device_list.h"

#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "opencl/device.h"

namespace kasha {

std::string device_list_syntax_error(const std::string& text) {
  if (text == "all") return "";
  if (text.empty() || text.back() == ',')
    return "give a device index, indices separated by commas (0,1) or all";
  std::stringstream list(text);
  size_t count = 0;
  for (std::string item; std::getline(list, item, ',');) {
    if (item.empty() || item.size() > 9 ||
        item.find_first_not_of("0123456789") != std::string::npos)
      return "\"" + printable(item) +
             "\" is not a device index (give indices separated by commas, or all)";
    if (++count > kMaxDeviceListEntries)
      return "more than " + std::to_string(kMaxDeviceListEntries) +
             " devices in the list (each entry is a render lane with its own copy of the scene)";
  }
  return "";
}

std::vector<int> parse_device_list(const std::string& text, int device_count) {
  const std::string wrong = device_list_syntax_error(text);
  if (!wrong.empty()) throw Error("--device " + printable(text) + ": " + wrong);
  std::vector<int> out;
  if (text == "all") {
    for (int i = 0; i < device_count; ++i) out.push_back(i);
    return out;
  }
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    const int index = std::stoi(item);
    if (index >= device_count)
      throw Error("--device " + printable(text) + ": no such OpenCL device " + item + " (" +
                  std::to_string(device_count) + " found; `kasha devices` lists them)");
    out.push_back(index);
  }
  return out;
}

std::vector<int> parse_device_list(const std::string& text) {
  return parse_device_list(text, static_cast<int>(list_devices().size()));
}

}  // namespace kasha
