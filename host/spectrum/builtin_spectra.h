#pragma once
// CIE illuminants compiled into the program (relative SPDs as published, D65 = 100 near 560 nm).
#include <string>
#include <vector>

#include "spectrum/spectrum.h"

namespace kasha {

// nullptr when `name` is not a built-in.
SpectrumPtr builtin_spectrum(const std::string& name);
std::vector<std::string> builtin_spectrum_names();

}  // namespace kasha
