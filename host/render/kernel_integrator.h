#pragma once
// What every OpenCL integrator shares: its program built for this scene and film, and the
// launches of its kernels on its device (render/kernel_launcher.h).
#include <string>

#include "render/integrator_registry.h"
#include "render/kernel_launcher.h"

namespace kasha {

class KernelIntegrator : public Integrator, protected KernelLauncher {
 public:
  double device_seconds() const override { return launched_seconds(); }
  std::string build_options() const override { return build_options_; }

 protected:
  // Builds kernels/<file> with the scene's definitions and `extra` ones.
  KernelIntegrator(const IntegratorSetup& setup, const std::string& file, KernelDefines extra = {});

  std::string build_options_;
  cl::Program program_;
};

}  // namespace kasha
