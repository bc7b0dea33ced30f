#pragma once
// `kasha devices` and `kasha info`: what the machine offers and what a scene needs.
#include <string>

namespace kasha {

int run_devices();
// Grid, features, geometry, kernel build options, record sizes and a memory estimate.
// `lamp`: one of the scene's "lamps" to switch on instead of its "lamp".
int run_info(const std::string& scene_path, bool spectral, const std::string& lamp);

}  // namespace kasha
