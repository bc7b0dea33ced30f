#pragma once
// A material's "normal_map" (docs/materials.md#normal-maps): pbrt-v4's tangent-space normals, an
// image whose RGB in [0, 1] is the normal 2·rgb − 1 in the frame (∂p/∂u, n × ∂p/∂u, n), read
// linear (PNG values are not sRGB-decoded), looked up bilinearly at (u, v), wrapping by repeating.
#include <string>
#include <vector>

#include "core/json_node.h"
#include "image/rgb_image.h"

namespace kasha {

struct NormalMap {
  std::string file;  // as resolved against the scene's folder
  RgbImage image;
};

// The normal map `node` names (a file, relative to the scene's folder), read once per file into
// `maps`; its index there. A file that cannot be read fails at `node`.
int read_normal_map(const JsonNode& node, std::vector<NormalMap>& maps);

}  // namespace kasha
