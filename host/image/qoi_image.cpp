#include "image/qoi_image.h"

#include <cstdlib>

#define QOI_IMPLEMENTATION
#define QOI_NO_STDIO
#include <qoi.h>

#include "core/error.h"
#include "core/printable.h"
#include "image/color_encoding.h"

namespace kasha {

RgbImage decode_qoi(const std::string& path, const std::string& bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 22 || bytes.compare(0, 4, "qoif") != 0)
    throw Error(printable(path) + ": not a QOI image");
  auto be32 = [&](int at) {
    return (static_cast<unsigned long long>(b[at]) << 24) | b[at + 1] << 16 | b[at + 2] << 8 |
           b[at + 3];
  };
  const unsigned long long width = be32(4), height = be32(8);
  if (width < 1 || height < 1 || width * height > kMaxScenePixels)
    throw Error(printable(path) + ": a QOI of " + std::to_string(width) + "x" +
                std::to_string(height) + " pixels (1 to 2^27 pixels)");
  if (bytes.size() > 0x7fffffff) throw Error(printable(path) + ": a QOI file beyond 2 GiB");
  // A run packs at most 62 pixels a byte; past its data the decoder would repeat the last pixel.
  if (width * height > 62 * bytes.size() + 65536)
    throw Error(printable(path) + ": its header claims " + std::to_string(width) + "x" +
                std::to_string(height) + " pixels, more than its " + std::to_string(bytes.size()) +
                " bytes can hold");
  qoi_desc desc{};
  auto* pixels = static_cast<unsigned char*>(
      qoi_decode(bytes.data(), static_cast<int>(bytes.size()), &desc, 3));
  if (!pixels) throw Error(printable(path) + ": a damaged QOI image");
  ColorEncoding encoding;
  if (desc.colorspace == QOI_LINEAR) encoding.kind = ColorEncoding::Kind::linear;
  float table[256];
  for (int i = 0; i < 256; ++i) table[i] = static_cast<float>(encoding.to_linear(i / 255.0));
  RgbImage out;
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  out.rgb.resize(3 * width * height);
  for (size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] = table[pixels[i]];
  std::free(pixels);
  return out;
}

}  // namespace kasha
