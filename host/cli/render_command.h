#pragma once
// `kasha render`: a scene through one integrator to an EXR (and PNG), with progress, Ctrl-C, a
// convergence log and a reference.
#include <string>

namespace kasha {

struct RenderArgs {
  std::string scene, output, png, integrator = "photon", view = "emission", reference, log;
  double seconds = 0;
  int passes = 0, spp = 16, device = 0;
  long long photons = 1 << 18;
  double alpha = 2.0 / 3.0, radius = 0;
  unsigned seed = 1;
  bool spectral = false;
  bool edge_correction = false;
  bool view_given = false;  // --view was on the command line
};

int run_render(const RenderArgs& args);

}  // namespace kasha
