#pragma once
// Whether a bench image is right (LuxMark validates its images the same way): its relMSE against
// the reference measured on block averages — 16 × 16 pixels, which takes the pixel noise of a
// short run down 256-fold while a wrong scale, a black image or a missing film row stay as large
// as they were — must not exceed the scene's bound, and every pixel must be finite.
#include <string>

#include "film/image.h"

namespace kasha {

// Pixels a side of the blocks validation compares (bench resolutions are multiples of it).
constexpr int kValidationBlock = 16;

struct Validation {
  double rel_mse =
      0;  // per pixel, as the convergence log's relmse (docs/formats.md#convergence-log)
  double block_rel_mse = 0;  // the same over kValidationBlock² block averages
  double bound = 0;
  bool finite = true;
  bool valid = false;
  std::string why;  // when not valid: what is wrong
};

// The mean of each block of `block` × `block` pixels (XYZ only); partial blocks at the right
// and bottom edges are averaged over the pixels they have.
Image block_average(const Image& image, int block);

// Throws kasha::Error (image_error's) when the sizes differ.
Validation validate_image(const Image& image, const Image& reference, double bound);

}  // namespace kasha
