#pragma once
// `kasha render`: a scene through one integrator to an EXR (and PNG), with progress, Ctrl-C, a
// convergence log and a reference.
#include <string>
#include <vector>

#include "render/integrator_registry.h"

namespace kasha {

struct RenderArgs {
  std::string scene, output, png, integrator = kDefaultIntegrator, reference, log, lamp;
  double seconds = 0;
  int passes = 0;
  std::string device = "0";  // --device: an index, a list or all (opencl/device_list.h)
  bool spectral = false;
  IntegratorSettings settings;
  // The integrator-specific options given on the command line (the chosen one must take them).
  std::vector<std::string> integrator_options_given;
};

int run_render(const RenderArgs& args);

}  // namespace kasha
