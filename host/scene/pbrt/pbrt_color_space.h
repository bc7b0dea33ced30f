#pragma once
// pbrt-v4's RGB colour spaces (its util/colorspace.cpp: srgb, rec2020, dci-p3, aces2065-1), each
// its primaries and white. kasha uplifts every RGB through its linear sRGB table
// (spectrum/rgb_spectrum.h), so an RGB given in another space becomes the sRGB triple of the same
// colour (docs/pbrt-import.md#spectra).
#include <array>
#include <string>

namespace kasha {

struct PbrtColorSpace {
  const char* name;
  std::array<double, 2> r, g, b, white;  // CIE 1931 xy chromaticities
};

// The space pbrt-v4 names `name` (case-insensitive, as pbrt-v4 reads it); null for another name.
const PbrtColorSpace* pbrt_color_space(const std::string& name);

// `rgb` in `space` as linear sRGB. An emitter's colour keeps its XYZ; a reflectance's (`adapt`)
// is carried by Bradford's chromatic adaptation from the space's white to D65: pbrt-v4 fits it to
// give `rgb` under the space's illuminant, kasha's table under D65.
std::array<double, 3> pbrt_rgb_to_srgb(const PbrtColorSpace& space,
                                       const std::array<double, 3>& rgb, bool adapt);

}  // namespace kasha
