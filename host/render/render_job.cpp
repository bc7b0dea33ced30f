#include "render/render_job.h"

#include "core/error.h"
#include "scene/medium_light_region.h"

namespace kasha {

// A physical integrator with no light to trace renders black: the same clear error for every one.
static const std::string& lit(const Scene& scene, const DeviceScene& device_scene,
                              const std::string& integrator) {
  if (IntegratorRegistry::find(integrator).traits.physical && device_scene.data().light_tri.empty())
    throw Error(scene.file + ": no emitter has power on the wavelength grid " +
                scene.grid.describe() + " (zero area, or emission outside the grid); the " +
                integrator + " integrator needs light");
  // Light tracing and photon mapping start light paths in emitting media too, at points of a
  // box that holds each: a medium emitting past every boundary has none.
  if (IntegratorRegistry::find(integrator).traits.medium_light_paths) {
    const std::vector<bool> used = scene.used_media();
    for (size_t m = 0; m < scene.media.size(); ++m)
      if (used[m] && !scene.media[m].emission.empty() &&
          !medium_light_region(scene, static_cast<int>(m)))
        throw Error(scene.medium_descs[m].where +
                    ": the medium emits and fills the space outside every shape, where no light "
                    "path of " +
                    integrator +
                    " can start (give it a shape that bounds it, or render with backward, vcm "
                    "or bpt)");
  }
  return integrator;
}

RenderJob::RenderJob(const std::vector<RenderLane>& lanes, const Scene& scene,
                     const std::string& integrator, const IntegratorSettings& settings,
                     bool spectral_film, const std::vector<Integrator*>& remote,
                     const IntegratorTestHooks& hooks)
    : film_(scene.camera.width, scene.camera.height, scene.grid, spectral_film,
            scene.camera.exposure),
      remote_(remote.size()) {
  if (lanes.empty()) throw Error("render: no device to render on");
  lit(scene, lanes[0].scene, integrator);
  for (const RenderLane& lane : lanes) {
    device_films_.push_back(std::make_unique<DeviceFilm>(lane.cl, film_));
    integrators_.push_back(IntegratorRegistry::make(
        integrator, IntegratorSetup{lane.cl, scene, lane.scene, *device_films_.back(), film_,
                                    settings, hooks}));
  }
  if (devices() == 1) return;
  std::vector<Integrator*> others;
  for (size_t i = 1; i < integrators_.size(); ++i) others.push_back(integrators_[i].get());
  others.insert(others.end(), remote.begin(), remote.end());
  if (!integrators_[0]->chunk_worker()) {
    std::vector<Integrator*> all{integrators_[0].get()};
    all.insert(all.end(), others.begin(), others.end());
    scheduler_ = std::make_unique<PassScheduler>(all);
    return;
  }
  std::vector<ChunkWorker*> helpers;
  for (Integrator* other : others) {
    if (!other->chunk_worker())
      throw Error(integrator + ": a helper device runs another integrator");
    helpers.push_back(other->chunk_worker());
  }
  integrators_[0]->set_helpers(helpers);
}

RenderSummary RenderJob::run(const RenderOptions& options) {
  if (!scheduler_) return render_progressive(*integrators_[0], film_, options);
  scheduler_->set_pass_limit(options.stop.passes);
  return render_progressive(*scheduler_, film_, options);
}

}  // namespace kasha
