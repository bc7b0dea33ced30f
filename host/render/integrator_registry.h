#pragma once
// Integrators by name (pbrt-v4's creation by name, Mitsuba's one-line registration): each
// integrator's host file registers itself with one KASHA_REGISTER_INTEGRATOR line giving its name,
// what it is, the command-line options it takes, its traits and its factory. The command line,
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
#include "shared_types.h"

namespace kasha {

// Every integrator's settings, filled by name; each integrator reads the ones it takes.
struct IntegratorSettings {
  int spp = 0;  // --spp: camera paths per pixel per pass (0: the integrator's default)
  static constexpr int kDefaultSpp = 16;  // backward's and debug's
  long long photons = 1 << 18;    // --photons: photons per pass
  double alpha = 0.8;  // --alpha: SPPM radius reduction (pbrt-v4: 2/3; 0.8 measured better here)
  double radius = 0;              // --radius: initial gather radius (0: from the pixel footprint)
  bool edge_correction = true;    // --edge-correction: photon mapping's gathers at edges
  std::string gather = "auto";    // --gather: where photon mapping gathers (device, host)
  std::string view = "emission";  // --view: the debug view
  unsigned seed = 1;              // --seed (every integrator)
  std::string sampler = "sobol";  // --sampler (every integrator): sobol or independent
  int max_depth = KASHA_MAX_PATH_DEPTH;  // --max-depth (every integrator): the path-length guard
  unsigned long long memory = 0;  // --memory: photon mapping's store budget, bytes (0: automatic)
  // Test hooks, not on the command line.
  bool full_matrix = false;   // backward: carry the full rows × N path matrix
  int photons_per_item = 64;  // forward: photons per work item
};

// What an integrator is given: the device, the scene on it, the film's tables on it, the film it
// will be accumulated into (photon mapping reads its radii there), and its settings.
struct IntegratorSetup {
  ClContext& cl;
  const Scene& scene;
  DeviceScene& device_scene;
  DeviceFilm& device_film;
  const Film& film;
  const IntegratorSettings& settings;
};

struct IntegratorTraits {
  bool physical =
      true;  // estimates the scene's light transport: converge, furnace and agreement tests
  bool unbiased = true;  // its mean is the image (else consistent: its bias falls with passes)
  bool sees_camera_mirrors = true;  // estimates what the camera sees in an ideal mirror
  bool reference = false;           // the one `kasha reference` renders with
};

struct IntegratorInfo {
  std::string name, description;
  std::vector<std::string> options;  // command-line options it takes besides the common ones
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
  // Every option some integrator takes.
  static std::vector<std::string> options();
  // Throws kasha::Error for the first of `given` (option names) the integrator does not take.
  static void check_options(const std::string& name, const std::vector<std::string>& given);

  struct Registrar {
    explicit Registrar(IntegratorInfo info);
  };

 private:
  static std::vector<IntegratorInfo>& entries();
};

constexpr const char* kDefaultIntegrator = "photon";

template <typename T>
std::unique_ptr<Integrator> make_integrator_of(const IntegratorSetup& setup) {
  return std::make_unique<T>(setup);
}

}  // namespace kasha

// One line in an integrator's host file: the class, then its name, description, options and traits.
#define KASHA_REGISTER_INTEGRATOR(CLASS, ...)                                  \
  static const ::kasha::IntegratorRegistry::Registrar kasha_registrar_##CLASS( \
      ::kasha::IntegratorInfo{__VA_ARGS__, ::kasha::make_integrator_of<CLASS>})
