#pragma once
// The spectrum value of docs/formats.md#spectrum-values: a number, a built-in name, or an object
// form with optional scale.
#include <string>
#include <vector>

#include "core/json_node.h"
#include "spectrum/spectrum.h"

namespace kasha {

// The largest spectrum value (after "scale") a scene may hold: float kernels multiply it by
// throughputs and areas, and float overflows at 3.4e38.
constexpr double kMaxSpectrumValue = 1e30;

// "a spectrum value of V is beyond 1e30": the one wording of the range error.
std::string spectrum_value_beyond(double value);

SpectrumPtr parse_spectrum(const JsonNode& node);

// A tabulated spectrum after checking that wavelengths increase and values are finite,
// non-negative and at most kMaxSpectrumValue; `where` prefixes error messages (a file and JSON
// path, or a file), then the sample's line in that file when `lines` gives them, and its nm.
SpectrumPtr make_tabulated_spectrum(const std::vector<double>& nm, const std::vector<double>& value,
                                    const std::string& where, const std::vector<int>& lines = {});

// Reads a spectrum from a delimited file: wavelength in the first column, the value in `column`
// (a header name, or empty for the only other column).
SpectrumPtr read_spectrum_csv(const std::string& path, const std::string& column = "");

}  // namespace kasha
