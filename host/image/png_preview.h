#pragma once
// The tone-mapped sRGB PNG preview: linear sRGB from XYZ, scaled so that the log-average
// luminance of the lit pixels maps to 0.18 (Reinhard's key) or by a given factor, clipped, and
// encoded with the sRGB transfer function, 8 bits.
#include <string>

#include "film/image.h"

namespace kasha {

// `scale` multiplies XYZ before the conversion (1 is then white at Y = 1); 0 chooses it by the key.
void write_png_preview(const std::string& path, const Image& image, double scale = 0);

}  // namespace kasha
