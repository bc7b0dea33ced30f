#pragma once
// `kasha measure`: fluorimeter or bispectral data to a material file
// (docs/measurement.md#the-equations, docs/formats.md#material-files).
#include <string>

namespace kasha {

struct MeasureArgs {
  std::string sample, etalon, etalon_reflectance, sensitivity, gloss, bispectral, output, plots,
      name;
  double band_nm = 0, cone_deg = 10;
  bool clip = false;
};

// A rank-1 residual (over the entries with signal) above this is reported as a sample that does not
// follow Kasha's rule.
constexpr double kRank1WarningResidual = 0.15;

int run_measure(const MeasureArgs& args);

}  // namespace kasha
