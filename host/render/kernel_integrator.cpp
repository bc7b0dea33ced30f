#include "render/kernel_integrator.h"

namespace kasha {

KernelIntegrator::KernelIntegrator(const IntegratorSetup& s, const std::string& file,
                                   KernelDefines extra)
    : cl_(s.cl), scene_(s.device_scene), film_(s.device_film) {
  KernelDefines defines = scene_defines(s.scene, film_.spectral());
  for (const auto& [name, value] : extra) defines[name] = value;
  program_ = build_program(cl_, assemble_kernel_source(file), defines, file);
}

}  // namespace kasha
