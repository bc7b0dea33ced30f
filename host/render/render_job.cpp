#include "render/render_job.h"

#include "core/error.h"

namespace kasha {

// A physical integrator with no light to trace renders black: the same clear error for every one.
static const std::string& lit(const Scene& scene, const DeviceScene& device_scene,
                              const std::string& integrator) {
  if (IntegratorRegistry::find(integrator).traits.physical && device_scene.data().light_tri.empty())
    throw Error(scene.file + ": no emitter has power on the wavelength grid " +
                scene.grid.describe() + " (zero area, or emission outside the grid); the " +
                integrator + " integrator needs light");
  return integrator;
}

RenderJob::RenderJob(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                     const std::string& integrator, const IntegratorSettings& settings,
                     bool spectral_film)
    : film_(scene.camera.width, scene.camera.height, scene.grid, spectral_film),
      device_film_(cl, film_),
      integrator_(IntegratorRegistry::make(
          lit(scene, device_scene, integrator),
          IntegratorSetup{cl, scene, device_scene, device_film_, film_, settings})) {}

}  // namespace kasha
