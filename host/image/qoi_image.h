#pragma once
// QOI images (.qoi) through Debian's qoi.h, as pbrt-v4 reads them (util/image.cpp ReadQOI): 8-bit
// RGB or RGBA, decoded by the header's own colour space (sRGB or linear), alpha dropped.
#include <string>

#include "image/rgb_image.h"

namespace kasha {

// The decoded image from a file's bytes; errors are kasha::Error "PATH: why". The header's size
// is checked before the decoder allocates.
RgbImage decode_qoi(const std::string& path, const std::string& bytes);

}  // namespace kasha
