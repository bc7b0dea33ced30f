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

static double exposure_for(const Image& image) {
  std::vector<float> y;
  for (size_t p = 0; p < image.pixels(); ++p)
    if (image.xyz[3 * p + 1] > 0 && std::isfinite(image.xyz[3 * p + 1]))
      y.push_back(image.xyz[3 * p + 1]);
  if (y.empty()) return 1.0;
  size_t k = std::min(y.size() - 1, static_cast<size_t>(0.99 * y.size()));
  std::nth_element(y.begin(), y.begin() + k, y.end());
  return y[k] > 0 ? 1.0 / y[k] : 1.0;
}

void write_png_preview(const std::string& path, const Image& image) {
  const double scale = exposure_for(image);
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
