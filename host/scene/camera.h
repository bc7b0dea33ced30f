#pragma once
// Pinhole camera of docs/formats.md#scenes: fov_deg spans the shorter image side, row 0 is the top,
// the image's right is forward × up, or up × forward with "mirror" (pbrt-v4's left-handed camera).
#include <array>

#include "core/json_node.h"
#include "scene/pixel_filter.h"
#include "shared/shared_types.h"

namespace kasha {

struct Camera {
  std::array<double, 3> position{0, 0, 0}, look_at{0, 0, 1}, up{0, 1, 0};
  double fov_deg = 40;
  int width = 256, height = 256;
  bool mirror = false;  // the image's right is up × forward
  PixelFilter filter;   // kasha's unit box unless "filter" names one of pbrt-v4's

  KCamera to_kernel() const;
};

Camera parse_camera(const JsonNode& node);

}  // namespace kasha
