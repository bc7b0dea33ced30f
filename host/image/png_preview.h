#pragma once
// The tone-mapped sRGB PNG preview: linear sRGB from XYZ, scaled so that the 99th percentile of
// luminance (Y) over the non-black pixels maps to 1 (so a visible lamp does not darken the rest),
// clipped, and encoded with the sRGB transfer function, 8 bits.
#include <string>

#include "film/image.h"

namespace kasha {

void write_png_preview(const std::string& path, const Image& image);

}  // namespace kasha
