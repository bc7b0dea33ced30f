#pragma once
// The results of `kasha colorimetry` as JSON (per illuminant "XYZ", "Lab", "whiteness", "tint",
// "beta"; at the top level for one illuminant, in "illuminants" for several), as a CSV table (a row
// per illuminant) and as the text table printed on stdout.
#include <nlohmann/json.hpp>
#include <string>

#include "colorimetry/sample_colorimetry.h"

namespace kasha {

nlohmann::json colorimetry_json(const Colorimetry& c, const std::string& material_file);
std::string colorimetry_csv(const Colorimetry& c);
std::string colorimetry_table(const Colorimetry& c, const std::string& material_file);

}  // namespace kasha
