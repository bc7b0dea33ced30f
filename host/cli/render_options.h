#pragma once
// The command-line options several commands share, declared in one place: the render settings
// gathered from the integrators' declarations (render/option_table.h), --device, and the bound on
// seconds.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "render/option_table.h"
#include "scene/pbrt/pbrt_import.h"

namespace kasha::cli {

// Seconds beyond this would overflow the steady clock's deadline (nanoseconds in 64 bits).
constexpr double kMaxSeconds = 1e9;

// Declares the render settings named in `names` (all of them when empty) on `app`, each with its
// help and its check.
void add_setting_options(CLI::App& app, IntegratorSettings& settings,
                         const std::vector<std::string>& names = {});

// The integrator-specific settings given on `app`'s command line (the chosen integrator must
// take each of them).
std::vector<std::string> integrator_options_given(const CLI::App& app);

// `--material NAME=FILE`, repeatable: a material of the scene (or a pbrt-v4 object's) replaced by a
// material file for this run.
CLI::Option* add_material_option(CLI::App& app, std::vector<MaterialOverride>& materials);

// `--device LIST`.
// --bin-nm W: the scene's wavelength grid with bins of W nm (render/render_spec.h).
CLI::Option* add_bin_option(CLI::App& app, double& bin_nm);
CLI::Option* add_device_option(CLI::App& app, std::string& device);

}  // namespace kasha::cli
