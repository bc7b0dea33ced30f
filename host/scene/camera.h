#pragma once
// The camera of docs/formats.md#camera, pbrt-v4's perspective (pinhole or thin lens),
// orthographic and spherical cameras: fov_deg spans the shorter image side unless a screen window
// says otherwise, row 0 is the top, the image's right is forward × up, or up × forward with
// "mirror" (pbrt-v4's left-handed camera).
#include <array>
#include <optional>
#include <string>

#include "core/json_node.h"
#include "scene/pixel_filter.h"
#include "shared/shared_types.h"

namespace kasha {

struct Camera {
  std::array<double, 3> position{0, 0, 0}, look_at{0, 0, 1}, up{0, 1, 0};
  double fov_deg = 40;
  int width = 256, height = 256;
  bool mirror = false;                // the image's right is up × forward
  std::string type = "perspective";   // "orthographic", "spherical"
  double lens_radius = 0;             // perspective: 0 for a pinhole
  double focal_distance = 1e6;        // pbrt-v4's default
  std::string mapping = "equalarea";  // spherical: or "equirectangular"
  // pbrt-v4's screen window (x0, x1, y0, y1): in units of tan(fov/2) (perspective) or of the
  // world (orthographic); unset: the shorter side spans [−1, 1].
  std::optional<std::array<double, 4>> screen_window;
  PixelFilter filter;   // kasha's unit box unless "filter" names one of pbrt-v4's
  double exposure = 1;  // what the image's values are multiplied by (pbrt-v4's imaging ratio)

  KCamera to_kernel() const;
};

Camera parse_camera(const JsonNode& node);

}  // namespace kasha
