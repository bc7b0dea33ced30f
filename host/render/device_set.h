#pragma once
// The devices a render runs on (`--device 0`, `0,1`, `all`): a context and a queue each — the same
// device named twice gets two, so rendering on several devices can be tested on one — and the
// scene uploaded to each. LuxCore's way: one render thread per device, one film.
#include <memory>
#include <string>
#include <vector>

#include "opencl/device.h"
#include "render/device_scene.h"

namespace kasha {

// One device a render runs on, with the scene on it.
struct RenderLane {
  ClContext& cl;
  DeviceScene& scene;
};

class DeviceSet {
 public:
  explicit DeviceSet(const std::vector<int>& indices);
  explicit DeviceSet(const std::string& list);  // as --device takes it (opencl/device_list.h)

  size_t size() const { return contexts_.size(); }
  ClContext& main() { return *contexts_[0]; }
  ClContext& operator[](size_t i) { return *contexts_[i]; }
  // "NAME" for one device, "NAME + NAME" for several.
  std::string names() const;

  // Uploads `scene` to every device (replacing the last one's); the lanes stay valid until the
  // next upload.
  std::vector<RenderLane> upload(const Scene& scene);
  void release_scene() { scenes_.clear(); }  // the lanes are invalid after this

 private:
  std::vector<std::unique_ptr<ClContext>> contexts_;
  std::vector<std::unique_ptr<DeviceScene>> scenes_;
};

}  // namespace kasha
