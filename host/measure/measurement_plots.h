#pragma once
// `kasha measure --plots DIR`: the method's figures as PNGs (raw matrix, the matrix with the band
// removed, passive reflectance, excitation, emission, the fit's residual), drawn by matplotlib
// from CSVs written next to them. Uses Debian's /usr/bin/python3 with python3-matplotlib.
#include <string>

#include "measure/measured_material.h"

namespace kasha {

// `who` names the folder in messages (the option and the folder given; `dir` may be a staging
// folder that is renamed to it).
void write_measurement_plots(const std::string& dir, const MeasuredMaterial& m,
                             const std::string& who);

}  // namespace kasha
