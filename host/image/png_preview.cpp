#include "image/png_preview.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "color/color_space.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace kasha {

// Reinhard's key: the log-average luminance of the lit pixels maps to 0.18, so mid-tones sit in
// the middle of the range whatever the scene's units; lamps and highlights clip.
static double exposure_for(const Image& image) {
  double sum = 0;
  size_t n = 0;
  for (size_t p = 0; p < image.pixels(); ++p) {
    double y = image.xyz[3 * p + 1];
    if (y > 0 && std::isfinite(y)) sum += std::log(y), ++n;
  }
  return n ? 0.18 / std::exp(sum / n) : 1.0;
}

void write_png_preview(const std::string& path, const Image& image, double exposure) {
  const double scale = exposure > 0 ? exposure : exposure_for(image);
  std::vector<unsigned char> pixels(3 * image.pixels());
  for (size_t p = 0; p < image.pixels(); ++p) {
    Vec3d rgb = xyz_to_linear_srgb(
        {image.xyz[3 * p] * scale, image.xyz[3 * p + 1] * scale, image.xyz[3 * p + 2] * scale});
    for (int k = 0; k < 3; ++k) {
      double v = std::isfinite(rgb[k]) ? srgb_encode(rgb[k]) : 0.0;
      pixels[3 * p + k] = static_cast<unsigned char>(std::lround(255.0 * v));
    }
  }
  write_atomically(path, [&](const std::string& tmp) {
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw Error(path + ": cannot open for writing");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      std::fclose(f);
      throw Error(path + ": PNG encoding failed");
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y)
      png_write_row(png, pixels.data() + 3 * static_cast<size_t>(y) * image.width);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(f) != 0) throw Error(path + ": write failed");
  });
}

}  // namespace kasha
