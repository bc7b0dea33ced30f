#include "image/pfm_image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

// The next whitespace-separated word of the header from `pos`, and `pos` past the one
// whitespace character that ends it (where the data of the last word starts).
std::string header_word(const std::string& bytes, size_t& pos) {
  while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
  const size_t start = pos;
  while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos])) &&
         pos - start < 32)
    ++pos;
  std::string word = bytes.substr(start, pos - start);
  if (pos < bytes.size()) ++pos;
  return word;
}

long long header_int(const std::string& path, const std::string& word, const char* what) {
  if (word.empty() || word.size() > 9 ||
      !std::all_of(word.begin(), word.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw Error(printable(path) + ": a PFM's " + what + " is not a whole number (\"" +
                printable(word) + "\")");
  return std::stoll(word);
}

}  // namespace

RgbImage decode_pfm(const std::string& path, const std::string& bytes) {
  size_t pos = 0;
  const std::string magic = header_word(bytes, pos);
  if (magic != "PF" && magic != "Pf")
    throw Error(printable(path) + ": not a PFM (it starts with neither \"PF\" nor \"Pf\")");
  const int channels = magic == "PF" ? 3 : 1;
  const long long width = header_int(path, header_word(bytes, pos), "width");
  const long long height = header_int(path, header_word(bytes, pos), "height");
  const std::string scale_word = header_word(bytes, pos);
  char* end = nullptr;
  const double scale = std::strtod(scale_word.c_str(), &end);
  if (scale_word.empty() || *end != '\0' || !std::isfinite(scale) || scale == 0)
    throw Error(printable(path) + ": a PFM's scale is not a nonzero number (\"" +
                printable(scale_word) + "\")");
  if (width < 1 || height < 1 || width * height > kMaxScenePixels)
    throw Error(printable(path) + ": a PFM of " + std::to_string(width) + "x" +
                std::to_string(height) + " pixels (1 to 2^27 pixels)");
  const size_t count = size_t(channels) * width * height;
  if (bytes.size() - pos < 4 * count)
    throw Error(printable(path) + ": a truncated PFM (" + std::to_string(bytes.size() - pos) +
                " bytes of pixels, " + std::to_string(4 * count) + " expected)");
  const bool little = scale < 0;
  RgbImage out;
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  out.rgb.resize(3 * size_t(width) * height);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + pos);
  for (size_t i = 0; i < count; ++i) {
    const unsigned char* b = data + 4 * i;
    const std::uint32_t bits = little ? b[0] | b[1] << 8 | b[2] << 16 | std::uint32_t(b[3]) << 24
                                      : b[3] | b[2] << 8 | b[1] << 16 | std::uint32_t(b[0]) << 24;
    float v;
    std::memcpy(&v, &bits, 4);
    const size_t pixel = i / channels;
    const long long x = pixel % width, y = height - 1 - static_cast<long long>(pixel / width);
    const double scaled = double(v) * std::abs(scale);
    if (!(std::abs(scaled) <= 3.4e38))
      throw Error(printable(path) + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                  ") is not finite");
    const float value = static_cast<float>(std::max(0.0, scaled));
    float* p = &out.rgb[3 * (size_t(y) * width + x)];
    if (channels == 1)
      p[0] = p[1] = p[2] = value;
    else
      p[i % 3] = value;
  }
  return out;
}

}  // namespace kasha
