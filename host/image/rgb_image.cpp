#include "image/rgb_image.h"

#include <stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "color/color_space.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "image/exr_io.h"
#include "image/pfm_image.h"
#include "image/qoi_image.h"

namespace kasha {

namespace {

std::string size_text(long long w, long long h) {
  return std::to_string(w) + "x" + std::to_string(h) + " pixels";
}

// stb's header check: the size before anything is decoded, within kMaxScenePixels.
void check_stb_size(const std::string& path, const std::string& bytes, const char* format) {
  int w = 0, h = 0, n = 0;
  if (bytes.size() > 0x7fffffff ||
      !stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                             static_cast<int>(bytes.size()), &w, &h, &n))
    throw Error(printable(path) + ": not a " + format + " image kasha can read");
  if (w < 1 || h < 1 || static_cast<long long>(w) * h > kMaxScenePixels)
    throw Error(printable(path) + ": " + size_text(w, h) + " (1 to 2^27 pixels)");
  // No format here packs more than ~8k pixels a byte (1-bit PNG, deflated): a header claiming
  // more than its file can hold would have stb allocate its size and fill it with zeros.
  if (static_cast<long long>(w) * h > 16384LL * static_cast<long long>(bytes.size()) + 65536)
    throw Error(printable(path) + ": its header claims " + size_text(w, h) + ", more than its " +
                std::to_string(bytes.size()) + " bytes can hold");
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

// 8- or 16-bit RGB through stb_image, each value decoded by `encoding`.
RgbImage read_stb_fixed(const std::string& path, const std::string& bytes,
                        const ColorEncoding& encoding, const char* format) {
  check_stb_size(path, bytes, format);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, n = 0;
  RgbImage out;
  if (stbi_is_16_bit_from_memory(data, size)) {
    std::unique_ptr<stbi_us, StbFree> p(stbi_load_16_from_memory(data, size, &w, &h, &n, 3));
    if (!p) throw Error(printable(path) + ": a damaged " + format + " image");
    out.rgb.resize(3 * size_t(w) * h);
    for (size_t i = 0; i < out.rgb.size(); ++i)
      out.rgb[i] = static_cast<float>(encoding.to_linear(p.get()[i] / 65535.0));
  } else {
    std::unique_ptr<stbi_uc, StbFree> p(stbi_load_from_memory(data, size, &w, &h, &n, 3));
    if (!p) throw Error(printable(path) + ": a damaged " + format + " image");
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = static_cast<float>(encoding.to_linear(i / 255.0));
    out.rgb.resize(3 * size_t(w) * h);
    for (size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] = table[p.get()[i]];
  }
  out.width = w;
  out.height = h;
  return out;
}

// Radiance HDR: stb's linear floats.
RgbImage read_hdr(const std::string& path, const std::string& bytes) {
  check_stb_size(path, bytes, "Radiance HDR");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  if (!stbi_is_hdr_from_memory(data, static_cast<int>(bytes.size())))
    throw Error(printable(path) + ": not a Radiance HDR image");
  int w = 0, h = 0, n = 0;
  std::unique_ptr<float, StbFree> p(
      stbi_loadf_from_memory(data, static_cast<int>(bytes.size()), &w, &h, &n, 3));
  if (!p) throw Error(printable(path) + ": a damaged Radiance HDR image");
  RgbImage out;
  out.width = w;
  out.height = h;
  out.rgb.resize(3 * size_t(w) * h);
  for (size_t i = 0; i < out.rgb.size(); ++i) {
    const float v = p.get()[i];
    if (!std::isfinite(v))
      throw Error(printable(path) + ": pixel (" + std::to_string(i / 3 % w) + ", " +
                  std::to_string(i / 3 / w) + ") is not finite");
    out.rgb[i] = std::max(0.0f, v);
  }
  return out;
}

RgbImage read_exr_rgb(const std::string& path) {
  const Image img = read_exr(path);  // XYZ, finite
  if (static_cast<long long>(img.width) * img.height > kMaxScenePixels)
    throw Error(printable(path) + ": " + size_text(img.width, img.height) +
                ", beyond the limit of 2^27");
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

}  // namespace

RgbImage read_rgb_image(const std::string& path, const ColorEncoding& png_encoding) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".exr") return read_exr_rgb(path);
  const std::string bytes = read_input_file(path, kMaxBinaryInputBytes);
  if (ext == ".pfm") return decode_pfm(path, bytes);
  if (ext == ".hdr") return read_hdr(path, bytes);
  if (ext == ".qoi") return decode_qoi(path, bytes);
  if (ext == ".png") return read_stb_fixed(path, bytes, png_encoding, "PNG");
  return read_stb_fixed(path, bytes, ColorEncoding{}, "TGA, JPEG, BMP, GIF or PNM");
}

}  // namespace kasha
