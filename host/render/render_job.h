#pragma once
// One integrator rendering one scene on one device into its film: the film, the film's tables on
// the device and the integrator made by name from the registry — what `render`, `converge`,
// `reference` and the tests set up.
#include <memory>
#include <string>

#include "film/film.h"
#include "render/device_film.h"
#include "render/integrator_registry.h"
#include "render/progressive_render.h"

namespace kasha {

class RenderJob {
 public:
  RenderJob(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
            const std::string& integrator, const IntegratorSettings& settings, bool spectral_film);
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  Film& film() { return film_; }
  const DeviceFilm& device_film() const { return device_film_; }
  Integrator& integrator() { return *integrator_; }
  // The progressive loop (render/progressive_render.h) over this job.
  RenderSummary run(const RenderOptions& options) {
    return render_progressive(*integrator_, film_, options);
  }
  // One pass, accumulated.
  void pass(int index) { film_.accumulate(integrator_->render_pass(index)); }

 private:
  Film film_;
  DeviceFilm device_film_;
  std::unique_ptr<Integrator> integrator_;
};

}  // namespace kasha
