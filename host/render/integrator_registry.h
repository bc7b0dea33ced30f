#pragma once
// Integrators by name (pbrt-v4's creation by name, Mitsuba's one-line registration): each
// integrator's host file registers itself with one KASHA_REGISTER_INTEGRATOR line giving its name,
// what it is, the declarations of the command-line options it takes (render/integrator_option.h),
// its traits and its factory. The command line,
// `converge`, `reference` and the tests all read this registry, so a new integrator is its kernel,
// its host file and that line.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "film/film.h"
#include "opencl/device.h"
#include "render/device_film.h"
#include "render/device_scene.h"
#include "render/integrator.h"
#include "render/integrator_option.h"
#include "render/integrator_test_hooks.h"
#include "render/render_settings.h"
#include "shared/shared_types.h"

namespace kasha {

// What an integrator is given: the device, the scene on it, the film's tables on it, the film it
// will be accumulated into (photon mapping reads its radii there), its settings and the tests'
// hooks.
struct IntegratorSetup {
  ClContext& cl;
  const Scene& scene;
  DeviceScene& device_scene;
  DeviceFilm& device_film;
  const Film& film;
  const IntegratorSettings& settings;
  const IntegratorTestHooks& hooks;
};

struct IntegratorTraits {
  bool physical =
      true;  // estimates the scene's light transport: converge, furnace and agreement tests
  bool unbiased = true;  // its mean is the image (else consistent: its bias falls with passes)
  bool sees_camera_mirrors = true;  // estimates what the camera sees in an ideal mirror
  bool reference = false;           // the one `kasha reference` renders with
  // Takes direct light by density estimation too (ppm, a baseline for comparing techniques): its
  // radius biases it most, so the bench leaves it out and the agreement tests allow it 3 times
  // the tolerance.
  bool direct_by_merges = false;
  // Takes the light seen through delta bounces alone (a lamp, its highlight in glass or a coat)
  // from extra samples where it has an edge (vcm and its modes): camera paths alone find it.
  bool samples_seen_light = false;
  // Its light paths start inside emitting media too (docs/media.md#emitting-media): it takes
  // their light from light paths (forward, photon mapping, ppm), so a medium that emits in a
  // region no box holds is refused. The others' camera paths take that light whole.
  bool medium_light_paths = false;
};

struct IntegratorInfo {
  std::string name, description;
  std::vector<IntegratorOption> options;  // the options it takes besides the common ones
  IntegratorTraits traits;
  std::function<std::unique_ptr<Integrator>(const IntegratorSetup&)> make;
};

class IntegratorRegistry {
 public:
  static const std::vector<IntegratorInfo>& all();  // sorted by name
  // Throws kasha::Error naming the known integrators.
  static const IntegratorInfo& find(const std::string& name);
  static std::vector<std::string> names(bool physical_only);
  static std::string reference();  // the reference integrator's name
  static std::unique_ptr<Integrator> make(const std::string& name, const IntegratorSetup& setup);
  // Throws kasha::Error for the first of `given` (option names) the integrator does not take.
  static void check_options(const std::string& name, const std::vector<std::string>& given);

  struct Registrar {
    explicit Registrar(IntegratorInfo info);
  };

 private:
  static std::vector<IntegratorInfo>& entries();
};

constexpr const char* kDefaultIntegrator = "vcm";

template <typename T>
std::unique_ptr<Integrator> make_integrator_of(const IntegratorSetup& setup) {
  return std::make_unique<T>(setup);
}

}  // namespace kasha

// One line in an integrator's host file: the class, then its name, description, options and traits.
#define KASHA_REGISTER_INTEGRATOR(CLASS, ...)                                  \
  static const ::kasha::IntegratorRegistry::Registrar kasha_registrar_##CLASS( \
      ::kasha::IntegratorInfo{__VA_ARGS__, ::kasha::make_integrator_of<CLASS>})
