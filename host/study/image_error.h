#pragma once
// Error of an image against a reference, as the convergence log reports it
// (docs/formats.md#convergence-log): RMSE over all pixels and X, Y, Z; relMSE = mean of (x − r)² /
// (r² + 0.01).
#include <cstddef>
#include <vector>

#include "film/image.h"

namespace kasha {

struct ImageError {
  double rmse = 0, relmse = 0;
  size_t pixels = 0;  // counted; with none (all left out) the two errors are 0, which means nothing
};

// Throws kasha::Error naming the reference's file when its size is not width x height, so a
// command can refuse it before rendering.
void check_reference_size(const Image& reference, int width, int height);

// Throws kasha::Error (as check_reference_size) when the sizes differ. With `leave_out` (a flag per
// pixel), those pixels are not counted.
ImageError image_error(const Image& image, const Image& reference,
                       const std::vector<bool>& leave_out = {});

}  // namespace kasha
