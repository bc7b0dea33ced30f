#include "image/rgb_image.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "color/color_space.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "image/exr_io.h"

namespace kasha {

static RgbImage read_png(const std::string& path) {
  const std::string bytes = read_input_file(path, kMaxBinaryInputBytes);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw Error(printable(path) + ": not a PNG kasha can read (" + image.message + ")");
  if (static_cast<long long>(image.width) * image.height > kMaxScenePixels) {
    png_image_free(&image);
    throw Error(printable(path) + ": " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " pixels, beyond the limit of 2^27");
  }
  // libpng's linear format: 16-bit linear RGB, decoded from sRGB (or the file's gamma).
  image.format = PNG_FORMAT_LINEAR_RGB;
  std::vector<png_uint_16> pixels(PNG_IMAGE_SIZE(image) / sizeof(png_uint_16));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
    throw Error(printable(path) + ": a damaged PNG (" + image.message + ")");
  RgbImage out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) out.rgb[i] = pixels[i] / 65535.0f;
  return out;
}

static RgbImage read_exr_rgb(const std::string& path) {
  const Image img = read_exr(path);  // XYZ, finite
  if (static_cast<long long>(img.width) * img.height > kMaxScenePixels)
    throw Error(printable(path) + ": " + std::to_string(img.width) + "x" +
                std::to_string(img.height) + " pixels, beyond the limit of 2^27");
  RgbImage out;
  out.width = img.width;
  out.height = img.height;
  out.rgb.resize(3 * img.pixels());
  for (size_t p = 0; p < img.pixels(); ++p) {
    Vec3d rgb = xyz_to_linear_srgb({img.xyz[3 * p], img.xyz[3 * p + 1], img.xyz[3 * p + 2]});
    for (int k = 0; k < 3; ++k) out.rgb[3 * p + k] = static_cast<float>(std::max(0.0, rgb[k]));
  }
  return out;
}

RgbImage read_rgb_image(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return read_png(path);
  if (ext == ".exr") return read_exr_rgb(path);
  throw Error(printable(path) + ": an image must be .png or .exr");
}

}  // namespace kasha
