#include "bench/bench_validation.h"

#include <cmath>
#include <cstdio>

#include "study/image_error.h"

namespace kasha {

Image block_average(const Image& image, int block) {
  Image out;
  out.width = (image.width + block - 1) / block;
  out.height = (image.height + block - 1) / block;
  out.source = image.source;
  std::vector<double> sum(3 * out.pixels(), 0.0);
  std::vector<int> count(out.pixels(), 0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const size_t b = static_cast<size_t>(y / block) * out.width + x / block;
      const size_t p = static_cast<size_t>(y) * image.width + x;
      for (int c = 0; c < 3; ++c) sum[3 * b + c] += image.xyz[3 * p + c];
      ++count[b];
    }
  out.xyz.resize(sum.size());
  for (size_t i = 0; i < sum.size(); ++i) out.xyz[i] = static_cast<float>(sum[i] / count[i / 3]);
  return out;
}

Validation validate_image(const Image& image, const Image& reference, double bound) {
  Validation v;
  v.bound = bound;
  for (float x : image.xyz) v.finite = v.finite && std::isfinite(x);
  v.rel_mse = image_error(image, reference).relmse;
  v.block_rel_mse = image_error(block_average(image, kValidationBlock),
                                block_average(reference, kValidationBlock))
                        .relmse;
  char why[160];
  if (!v.finite) {
    v.why = "the image has non-finite pixels";
  } else if (!(v.block_rel_mse <= bound)) {
    std::snprintf(why, sizeof why, "relMSE of %dx%d block means %.3g is above the bound %.3g",
                  kValidationBlock, kValidationBlock, v.block_rel_mse, bound);
    v.why = why;
  }
  v.valid = v.why.empty();
  return v;
}

}  // namespace kasha
