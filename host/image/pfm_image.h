#pragma once
// Portable float maps (.pfm), read as pbrt-v4 reads them (util/image.cpp ReadPFM): "PF" (RGB) or
// "Pf" (grey), width, height and a scale whose sign gives the byte order (negative: little
// endian) and whose magnitude multiplies the values; rows stored from the bottom up.
#include <string>

#include "image/rgb_image.h"

namespace kasha {

// The decoded image from a file's bytes: linear, grey replicated to RGB, negatives 0. Errors are
// kasha::Error "PATH: why"; the size is checked before anything is allocated.
RgbImage decode_pfm(const std::string& path, const std::string& bytes);

}  // namespace kasha
