#pragma once
// The tone-mapped sRGB PNG preview: linear sRGB from XYZ, scaled so that the log-average
// luminance of the lit pixels maps to 0.18 (Reinhard's key), clipped, and encoded with the sRGB
// transfer function, 8 bits.
#include <string>

#include "film/image.h"

namespace kasha {

void write_png_preview(const std::string& path, const Image& image);

}  // namespace kasha
