#include "render/render_job.h"

namespace kasha {

RenderJob::RenderJob(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                     const std::string& integrator, const IntegratorSettings& settings,
                     bool spectral_film)
    : film_(scene.camera.width, scene.camera.height, scene.grid, spectral_film),
      device_film_(cl, film_),
      integrator_(IntegratorRegistry::make(
          integrator, IntegratorSetup{cl, scene, device_scene, device_film_, film_, settings})) {}

}  // namespace kasha
