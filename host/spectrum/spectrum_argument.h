#pragma once
// A spectrum given on the command line: any spectrum value of docs/formats.md#spectrum-values
// written as JSON
// ('{"blackbody_K": 6500}', 0.5), a built-in name (D65, A, F11, …), or the path of a CSV file
// (two columns, nm and value).
#include <string>

#include "spectrum/spectrum.h"

namespace kasha {

// `option` names the option in error messages.
SpectrumPtr parse_spectrum_argument(const std::string& text, const std::string& option);

}  // namespace kasha
