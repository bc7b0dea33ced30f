#pragma once
// The plumbing every OpenCL integrator shares: its program built for this scene and film, and
// launches that set the scene's and the film's parameters (KASHA_SCENE_PARAMS,
// KASHA_FILM_PARAMS) before the kernel's own arguments.
#include <string>

#include "render/integrator_registry.h"

namespace kasha {

class KernelIntegrator : public Integrator {
 protected:
  // Builds kernels/<file> with the scene's definitions and `extra` ones.
  KernelIntegrator(const IntegratorSetup& setup, const std::string& file, KernelDefines extra = {});

  // Sets the scene's and the film's parameters, then `args` in order; enqueues `items` work items.
  template <typename... Args>
  void launch(cl::Kernel& kernel, size_t items, const Args&... args) {
    cl_uint a = static_cast<cl_uint>(film_.bind(kernel, scene_.bind(kernel, 0)));
    (kernel.setArg(a++, args), ...);
    cl_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items));
  }

  ClContext& cl_;
  DeviceScene& scene_;
  DeviceFilm& film_;
  cl::Program program_;
};

}  // namespace kasha
