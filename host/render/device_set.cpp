#include "render/device_set.h"

#include "opencl/device_list.h"

namespace kasha {

DeviceSet::DeviceSet(const std::vector<int>& indices) {
  for (int i : indices) contexts_.push_back(std::make_unique<ClContext>(i));
}

DeviceSet::DeviceSet(const std::string& list) : DeviceSet(parse_device_list(list)) {}

std::string DeviceSet::names() const {
  std::string out;
  for (const auto& c : contexts_) out += (out.empty() ? "" : " + ") + c->info().name;
  return out;
}

std::vector<RenderLane> DeviceSet::upload(const Scene& scene) {
  scenes_.clear();
  std::vector<RenderLane> lanes;
  for (auto& c : contexts_) {
    scenes_.push_back(std::make_unique<DeviceScene>(*c, scene));
    lanes.push_back({*c, *scenes_.back()});
  }
  return lanes;
}

}  // namespace kasha
