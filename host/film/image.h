#pragma once
// A finished image: per-pixel XYZ (docs/formats.md#images convention, no 683 factor) and, for a
// spectral film, per-bin radiance. Linear sRGB is derived from XYZ when written.
#include <string>
#include <vector>

#include "spectrum/wavelength_grid.h"

namespace kasha {

struct Image {
  int width = 0, height = 0;
  std::vector<float> xyz;       // 3 per pixel, row 0 at the top
  std::vector<float> spectral;  // grid.bins per pixel, or empty
  WavelengthGrid grid;          // meaningful when spectral is not empty
  std::string source;           // the file it was read from, for messages; empty when rendered

  size_t pixels() const { return static_cast<size_t>(width) * height; }
  bool has_spectral() const { return !spectral.empty(); }
};

}  // namespace kasha
