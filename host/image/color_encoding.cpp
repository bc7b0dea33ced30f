#include "image/color_encoding.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

double ColorEncoding::to_linear(double v) const {
  switch (kind) {
    case Kind::linear:
      return v;
    case Kind::gamma:
      return std::pow(v, gamma);
    case Kind::srgb:
      break;
  }
  // The sRGB transfer function's inverse (IEC 61966-2-1), as pbrt-v4's SRGBToLinear.
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

ColorEncoding parse_color_encoding(const std::string& name) {
  ColorEncoding e;
  if (name == "sRGB") return e;
  if (name == "linear") {
    e.kind = ColorEncoding::Kind::linear;
    return e;
  }
  std::istringstream in(name);
  std::string word, rest;
  double g = 0;
  if (in >> word && word == "gamma" && in >> g && !(in >> rest) && std::isfinite(g) && g != 0) {
    e.kind = ColorEncoding::Kind::gamma;
    e.gamma = g;
    return e;
  }
  throw Error("unknown color encoding \"" + printable(name) +
              "\" (sRGB, linear, \"gamma G\" with G a nonzero number)");
}

}  // namespace kasha
