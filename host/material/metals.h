#pragma once
// Measured complex refractive indices of metals, built in (host/data/metal_*.csv, from pbrt-v4's
// tables; host/data/SOURCES.md): what a conductor's "metal" names.
#include <string>
#include <vector>

#include "spectrum/spectrum.h"

namespace kasha {

struct MetalIndex {
  SpectrumPtr eta, k;
};

// The metal's n and k, held at the table's end values beyond its 298.8–885.6 nm (so any grid sees
// a finite, non-zero index); an empty MetalIndex when `name` is not a built-in metal.
MetalIndex builtin_metal(const std::string& name);
std::vector<std::string> builtin_metal_names();

}  // namespace kasha
