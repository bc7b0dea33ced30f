#pragma once
// One integrator rendering one scene into its film on one device or several: the film, the
// film's tables on each device and an instance of the integrator made by name from the registry
// on each — what `render`, `converge`, `bench`, `reference` and the tests set up. On several
// devices, independent passes are handed out whole (render/pass_scheduler.h); photon mapping
// shares each pass's photons among its instances. Either way the image is the one device's, bit
// for bit, for the same seed and passes. Under MPI, rank 0's job also takes the other ranks'
// devices as lanes (mpi/remote_lane.h), after its own.
#include <memory>
#include <string>
#include <vector>

#include "film/film.h"
#include "render/device_film.h"
#include "render/device_set.h"
#include "render/integrator_registry.h"
#include "render/pass_scheduler.h"
#include "render/progressive_render.h"

namespace kasha {

class RenderJob {
 public:
  // `remote`: lanes whose instances live elsewhere (other MPI ranks); they outlive the job.
  RenderJob(const std::vector<RenderLane>& lanes, const Scene& scene, const std::string& integrator,
            const IntegratorSettings& settings, bool spectral_film,
            const std::vector<Integrator*>& remote = {}, const IntegratorTestHooks& hooks = {});
  RenderJob(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
            const std::string& integrator, const IntegratorSettings& settings, bool spectral_film,
            const IntegratorTestHooks& hooks = {})
      : RenderJob({RenderLane{cl, device_scene}}, scene, integrator, settings, spectral_film, {},
                  hooks) {}
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  Film& film() { return film_; }
  const Film& film() const { return film_; }
  // The first device's instance (its name, figures and buffers stand for all).
  Integrator& integrator(size_t lane = 0) { return *integrators_[lane]; }
  size_t devices() const { return integrators_.size() + remote_; }  // remote lanes last
  size_t local_devices() const { return integrators_.size(); }
  // The film's tables on local device `lane` (their bytes count in bench's device memory).
  const DeviceFilm& device_film(size_t lane = 0) const { return *device_films_[lane]; }
  // The progressive loop (render/progressive_render.h) over this job.
  RenderSummary run(const RenderOptions& options);
  // One pass on the first device, accumulated.
  void pass(int index) { film_.accumulate(integrators_[0]->render_pass(index)); }

 private:
  Film film_;
  std::vector<std::unique_ptr<DeviceFilm>> device_films_;
  std::vector<std::unique_ptr<Integrator>> integrators_;
  std::unique_ptr<PassScheduler> scheduler_;  // several devices, independent passes
  size_t remote_ = 0;
};

}  // namespace kasha
