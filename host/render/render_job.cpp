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
  // Light tracing and photon mapping carry light that starts at lights and emitters only: an
  // emitting medium's light, scattered before the camera path meets it, they never find.
  if (const int m = scene.emitting_medium();
      m >= 0 && !IntegratorRegistry::find(integrator).traits.sees_medium_emission)
    throw Error(scene.medium_descs[m].where + ": the medium emits, and " + integrator +
                " takes light from light paths, which start only at lights and emitters: render "
                "it with backward, vcm or bpt");
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
