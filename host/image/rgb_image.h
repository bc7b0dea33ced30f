#pragma once
// Images that scenes read — environment maps and textures — as linear sRGB, by their extension
// as pbrt-v4 reads them (util/image.cpp Image::Read): OpenEXR (its R, G, B channels, or its XYZ
// layer converted); PFM (image/pfm_image.h); Radiance HDR (linear floats, via stb_image); QOI
// (image/qoi_image.h); PNG (8 or 16 bits, decoded by the given encoding, sRGB by default); every
// other extension through stb_image (TGA, JPEG, BMP, GIF, PNM, 8-bit, always sRGB as in pbrt-v4).
// Grey is replicated to RGB and alpha dropped. Negative values (filtering overshoot in EXRs)
// count as 0; a value that is not finite is an error naming the pixel.
#include <string>
#include <vector>

#include "image/color_encoding.h"

namespace kasha {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 per pixel, row 0 at the top

  const float* at(int x, int y) const { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
};

// The largest image a scene may read, in pixels (a 16k × 8k environment map).
constexpr long long kMaxScenePixels = 1LL << 27;

// Errors are kasha::Error "PATH: why"; a size is checked before the pixels are allocated,
// against the limit and against what the file's bytes can hold.
RgbImage read_rgb_image(const std::string& path, const ColorEncoding& png_encoding = {});

}  // namespace kasha
