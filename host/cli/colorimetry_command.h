#pragma once
// `kasha colorimetry`: a material's total radiance factor, XYZ, CIELAB and CIE whiteness/tint under
// each illuminant, and ΔE2000 against its "as is" material.
#include <string>
#include <vector>

namespace kasha {

struct ColorimetryArgs {
  std::string material, json, csv, plot, as_is, write_as_is;
  std::vector<std::string> illuminants;  // default: D65
  int observer = 2;                      // 2 or 10 (degrees)
  double bin_nm = 10;
};

int run_colorimetry(const ColorimetryArgs& args);

}  // namespace kasha
