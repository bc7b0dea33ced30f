#pragma once
// How an image's 8- and 16-bit values become linear values (pbrt-v4's ColorEncoding,
// util/color.h): the sRGB transfer function, linear, or a power "gamma G". Float images (EXR,
// PFM, HDR) are linear and ignore it.
#include <string>

namespace kasha {

struct ColorEncoding {
  enum class Kind { srgb, linear, gamma };
  Kind kind = Kind::srgb;
  double gamma = 1;  // Kind::gamma: linear = value^gamma

  // A value in [0, 1] as stored, decoded to linear.
  double to_linear(double v) const;
};

// pbrt-v4's names: "sRGB", "linear", "gamma G" (G a nonzero number). Throws kasha::Error with
// the reason, without a file name, for an unknown one.
ColorEncoding parse_color_encoding(const std::string& name);

}  // namespace kasha
