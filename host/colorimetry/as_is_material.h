#pragma once
// The "as is" material of the seed paper's Figure 8: a fluorescent sample taken at face value from
// a plain reflectance measurement — its total radiance factor β under one lamp, fluorescence folded
// in — as a passive material. It matches the sample under that lamp and misses how the
// fluorescence changes under any other.
#include <string>
#include <vector>

#include "material/material.h"

namespace kasha {

struct AsIsMaterial {
  std::string lamp;                 // the lamp β was taken under
  MaterialDesc desc;                // passive reflectance per bin (a step function), gloss kept
  std::vector<double> reflectance;  // the same per bin, on the grid it was made on
  std::vector<double> table_nm, table_value;  // the step function's corners, as the file holds them
  // β above 1 − g (energy conservation) is clipped there; bin centres where that happened.
  std::vector<double> clipped_nm;
  // Bins the lamp leaves unlit where the sample fluoresces: β is undefined, ρ is taken.
  std::vector<double> unlit_nm;
};

AsIsMaterial as_is_material(const Material& material, const std::vector<double>& lamp,
                            const WavelengthGrid& grid, const std::string& lamp_label);

// A material file (docs/formats.md#material-files) with the reflectance and, in "diagnostics",
// where it came from.
void write_as_is_material(const std::string& path, const AsIsMaterial& as_is,
                          const std::string& source);

}  // namespace kasha
