#include "render/kernel_integrator.h"

#include "core/error.h"

namespace kasha {

KernelIntegrator::KernelIntegrator(const IntegratorSetup& s, const std::string& file,
                                   KernelDefines extra)
    : KernelLauncher(s.cl, s.device_scene, s.device_film) {
  KernelDefines defines = scene_defines(s.scene, film_.spectral());
  if (s.settings.sampler != "sobol" && s.settings.sampler != "independent")
    throw Error("--sampler " + s.settings.sampler + ": unknown sampler (sobol, independent)");
  defines["KASHA_SOBOL"] = s.settings.sampler == "sobol" ? "1" : "0";
  defines["KASHA_MAX_PATH_DEPTH"] = std::to_string(s.settings.max_depth);
  for (const auto& [name, value] : extra) defines[name] = value;
  build_options_ = kasha::build_options(defines);
  program_ = build_program(cl_, assemble_kernel_source(file), defines, file);
}

}  // namespace kasha
