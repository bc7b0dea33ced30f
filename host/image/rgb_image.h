#pragma once
// Images that scenes read — environment maps and textures — as linear sRGB: PNG (8 or 16 bits,
// grey or colour, with or without alpha, decoded from sRGB or the file's own gamma by libpng) and
// OpenEXR (its R, G, B channels, or its XYZ layer converted). Negative values (filtering
// overshoot in EXRs) count as 0; a value that is not finite is an error naming the pixel.
#include <string>
#include <vector>

namespace kasha {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 per pixel, row 0 at the top

  const float* at(int x, int y) const { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
};

// The largest image a scene may read, in pixels (a 16k × 8k environment map).
constexpr long long kMaxScenePixels = 1LL << 27;

// Reads a .png or .exr (by its extension, any case); errors are kasha::Error "PATH: why".
RgbImage read_rgb_image(const std::string& path);

}  // namespace kasha
