#pragma once
// The physical integrators by name, as `render` and `converge` choose them.
#include <memory>
#include <string>

#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/integrator.h"

namespace kasha {

struct IntegratorSettings {
  int spp = 16;                 // backward: camera paths per pixel per pass
  long long photons = 1 << 18;  // forward, photon: photons per pass
  double alpha = 2.0 / 3.0, radius = 0;
  unsigned seed = 1;
  bool edge_correction = false;  // photon mapping
};

// backward, forward or photon; throws kasha::Error naming the known ones otherwise.
std::unique_ptr<Integrator> make_integrator(const std::string& name, ClContext& cl,
                                            const Scene& scene, DeviceScene& device_scene,
                                            const Film& film, const IntegratorSettings& settings);

}  // namespace kasha
