#include "scene/normal_map.h"

#include <filesystem>

#include "core/error.h"

namespace kasha {

int read_normal_map(const JsonNode& node, std::vector<NormalMap>& maps) {
  const std::filesystem::path file = node.file_path();
  for (size_t i = 0; i < maps.size(); ++i)
    if (maps[i].file == file.string()) return static_cast<int>(i);
  NormalMap m;
  m.file = file.string();
  // pbrt-v4 reads normal maps with ColorEncoding::Linear: a byte b is the value b / 255.
  ColorEncoding linear;
  linear.kind = ColorEncoding::Kind::linear;
  try {
    m.image = read_rgb_image(m.file, linear);
  } catch (const Error& e) {
    node.fail(e.what());
  }
  maps.push_back(std::move(m));
  return static_cast<int>(maps.size()) - 1;
}

}  // namespace kasha
