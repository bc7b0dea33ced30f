#pragma once
// Writes a measured material as a kasha material file (docs/formats.md#material-files), diagnostics
// included.
#include <string>

#include "measure/measured_material.h"

namespace kasha {

void write_material_file(const std::string& path, const std::string& name,
                         const MeasuredMaterial& m);

}  // namespace kasha
