#include "study/image_error.h"

#include <cmath>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

void check_reference_size(const Image& reference, int width, int height) {
  if (reference.width != width || reference.height != height)
    throw Error((reference.source.empty() ? "" : printable(reference.source) + ": ") +
                "the reference is " + std::to_string(reference.width) + "x" +
                std::to_string(reference.height) + " but the image is " + std::to_string(width) +
                "x" + std::to_string(height));
}

ImageError image_error(const Image& image, const Image& reference,
                       const std::vector<bool>& leave_out) {
  check_reference_size(reference, image.width, image.height);
  double se = 0, rel = 0;
  size_t n = 0;
  for (size_t i = 0; i < image.xyz.size(); ++i) {
    if (!leave_out.empty() && leave_out[i / 3]) continue;
    ++n;
    double d = static_cast<double>(image.xyz[i]) - reference.xyz[i];
    se += d * d;
    rel += d * d / (static_cast<double>(reference.xyz[i]) * reference.xyz[i] + 0.01);
  }
  if (n == 0) return {0, 0, 0};
  return {std::sqrt(se / n), rel / n, n / 3};
}

}  // namespace kasha
