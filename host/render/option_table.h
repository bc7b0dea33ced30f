#pragma once
// The render options, gathered from the integrators' declarations (render/integrator_option.h)
// and the common ones: what the command line declares (cli/render_options.h), with a help line
// assembled from every declaration's help and default, and what MPI ranks compare.
#include <string>
#include <vector>

#include "render/integrator_option.h"

namespace kasha {

struct RenderOption {
  IntegratorOption option;          // the first declaration, its help the assembled one
  std::vector<std::string> takers;  // the integrators declaring it; empty: every integrator's
  bool common() const { return takers.empty(); }
};

// The integrators' options (in the registry's order, each where first declared), then the common
// ones. Throws std::logic_error where two declarations of an option disagree on its value kind,
// range or setting.
const std::vector<RenderOption>& render_options();

// The settings' values as text, the device's own left out: what a render's image depends on
// besides its scene, integrator and film.
std::string settings_fingerprint(const IntegratorSettings& settings);

}  // namespace kasha
