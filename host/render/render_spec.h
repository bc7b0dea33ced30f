#pragma once
// What a render is, apart from where its results go: the scene and its lamp, the integrator and
// its settings, the film, when to stop and the devices. The command line fills it (cli/
// render_command.cpp); under MPI, ranks > 0 render from their own and compare it with rank 0's by
// its fingerprint (mpi/render_server.h).
#include <optional>
#include <string>

#include "render/integrator_registry.h"
#include "render/pass_control.h"
#include "render/render_settings.h"
#include "scene/pbrt/pbrt_import.h"

namespace kasha {

struct RenderSpec {
  std::string scene, lamp, integrator = kDefaultIntegrator;
  bool spectral = false;  // one channel per wavelength bin in the film
  StopCondition stop;
  std::string device = "0";  // an index, a list or all (opencl/device_list.h)
  IntegratorSettings settings;
  std::vector<MaterialOverride> materials;  // --material NAME=FILE
  double bin_nm = 0;  // --bin-nm: the wavelength bins' width, the range automatic (0: the scene's)

  // The grid the scene is loaded on: the scene's own, or --bin-nm's.
  std::optional<GridRequest> grid() const;
};

// What the image depends on, as text: the scene's path, its lamp, the integrator, the film and
// every setting but the devices and their memory. Ranks whose renders differ would not add up to
// one image.
std::string render_fingerprint(const RenderSpec& spec);

}  // namespace kasha
