#pragma once
// The spectrum value of DESIGN §5: a number, a built-in name, or an object form with optional
// scale.
#include <string>
#include <vector>

#include "core/json_node.h"
#include "spectrum/spectrum.h"

namespace kasha {

SpectrumPtr parse_spectrum(const JsonNode& node);

// A tabulated spectrum after checking that wavelengths increase and values are finite and
// non-negative; `where` prefixes error messages (a file and JSON path, or a file and line).
SpectrumPtr make_tabulated_spectrum(const std::vector<double>& nm, const std::vector<double>& value,
                                    const std::string& where);

// Reads a spectrum from a delimited file: wavelength in the first column, the value in `column`
// (a header name, or empty for the only other column).
SpectrumPtr read_spectrum_csv(const std::string& path, const std::string& column = "");

}  // namespace kasha
