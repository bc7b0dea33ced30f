#pragma once
// The camera's pixel filter (docs/formats.md#camera): kasha's own unit box by default, or one of
// pbrt-v4's filters (box, triangle, gaussian, mitchell, lanczos) with pbrt-v4's parameters. The
// kernels sample and splat it as geometry/pixel_filter.h says; box and triangle are exact, the
// others a table of 16 bins per half axis of the filter's positive part.
#include <array>
#include <string>

#include "core/json_node.h"
#include "shared/shared_types.h"

namespace kasha {

struct PixelFilter {
  std::string type;  // "" (kasha's unit box), box, triangle, gaussian, mitchell, lanczos
  std::array<double, 2> radius{0.5, 0.5};
  double sigma = 0.5;               // gaussian
  double b = 1.0 / 3, c = 1.0 / 3;  // mitchell
  double tau = 3;                   // lanczos

  // Whether the filter has negative lobes, which kasha leaves out (mitchell, lanczos).
  bool has_negative_lobes() const { return type == "mitchell" || type == "lanczos"; }
  // The filter along one axis at offset x in pixels (pbrt-v4's Evaluate, one factor).
  double evaluate_1d(int axis, double x) const;
  void to_kernel(KCamera* out) const;
};

// Whether `type` names one of pbrt-v4's filters (box, triangle, gaussian, mitchell, lanczos).
bool is_pixel_filter(const std::string& type);
// pbrt-v4's defaults for a filter type: the radius and shape parameters its Create reads.
PixelFilter default_pixel_filter(const std::string& type);
PixelFilter parse_pixel_filter(const JsonNode& node);

}  // namespace kasha
