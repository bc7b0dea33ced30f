#include "render/integrator_factory.h"

#include "core/error.h"
#include "render/backward_integrator.h"
#include "render/forward_integrator.h"
#include "render/photon_map_integrator.h"

namespace kasha {

std::unique_ptr<Integrator> make_integrator(const std::string& name, ClContext& cl,
                                            const Scene& scene, DeviceScene& device_scene,
                                            const Film& film, const IntegratorSettings& s) {
  if (name == "backward")
    return std::make_unique<BackwardIntegrator>(cl, scene, device_scene, film, s.spp, s.seed);
  if (name == "forward")
    return std::make_unique<ForwardIntegrator>(cl, scene, device_scene, film, s.photons, s.seed);
  if (name == "photon")
    return std::make_unique<PhotonMapIntegrator>(
        cl, scene, device_scene, film,
        PhotonMapSettings{s.photons, s.alpha, s.radius, s.seed, s.edge_correction});
  throw Error("unknown integrator \"" + name + "\" (backward, forward, photon)");
}

}  // namespace kasha
