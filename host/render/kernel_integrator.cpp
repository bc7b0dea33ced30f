#include "render/kernel_integrator.h"

#include "render/depth_cap.h"

namespace kasha {

KernelIntegrator::KernelIntegrator(const IntegratorSetup& s, const std::string& file,
                                   KernelDefines extra)
    : KernelLauncher(s.cl, s.device_scene, s.device_film) {
  KernelDefines defines = scene_defines(s.scene, film_.spectral());
  defines["KASHA_SOBOL"] = s.settings.sampler == Sampler::sobol ? "1" : "0";
  defines["KASHA_MAX_PATH_DEPTH"] = std::to_string(s.settings.depth_guard);
  // Defined only under a cap, so that the default kernels stay the unbiased ones.
  const int cap = depth_cap(s.settings, s.scene);
  if (cap != IntegratorSettings::kNoDepthCap) defines["KASHA_DEPTH_CAP"] = std::to_string(cap);
  for (const auto& [name, value] : extra) defines[name] = value;
  build_options_ = kasha::build_options(defines);
  program_ = build_program(cl_, assemble_kernel_source(file), defines, file);
}

}  // namespace kasha
