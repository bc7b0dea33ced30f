#pragma once
// The render settings' values: every option an integrator or every integrator takes, as the
// command line fills them. Each integrator declares its own options beside its registration line
// (render/integrator_option.h); the options every integrator takes (--seed, --max-depth,
// --sampler) are declared once, here. Enumerations are parsed once, into the enums below.
#include <string>
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

enum class Sampler { sobol, independent };
enum class Gather { automatic, device, host };  // photon mapping's gather
enum class Merges { automatic, caustic, first, every };
enum class DebugView { emission, normals, albedo };

// An enum's names on the command line, in the order of its values.
template <typename E>
const std::vector<std::string>& choice_names();
template <>
inline const std::vector<std::string>& choice_names<Sampler>() {
  static const std::vector<std::string> names{"sobol", "independent"};
  return names;
}
template <>
inline const std::vector<std::string>& choice_names<Gather>() {
  static const std::vector<std::string> names{"auto", "device", "host"};
  return names;
}
template <>
inline const std::vector<std::string>& choice_names<Merges>() {
  static const std::vector<std::string> names{"auto", "caustic", "first", "every"};
  return names;
}
template <>
inline const std::vector<std::string>& choice_names<DebugView>() {
  static const std::vector<std::string> names{"emission", "normals", "albedo"};
  return names;
}
template <typename E>
const std::string& choice_name(E value) {
  return choice_names<E>()[static_cast<size_t>(value)];
}

// Every option's value; 0 where an integrator's default depends on the scene or the integrator.
struct IntegratorSettings {
  int spp = 0;            // --spp: camera paths per pixel per pass (0: the integrator's default)
  long long photons = 0;  // --photons: photons (vcm: light subpaths) per pass (0: the default)
  // SPPM radius reduction (pbrt-v4: 2/3; 0.8 measured better here).
  static constexpr double kDefaultAlpha = 0.8;
  double alpha = kDefaultAlpha;  // --alpha
  double radius = 0;             // --radius: initial gather radius (0: from the pixel footprint)
  bool edge_correction = true;   // --edge-correction: gathers and merges at edges
  Gather gather = Gather::automatic;
  Merges merges = Merges::automatic;
  DebugView view = DebugView::emission;
  unsigned seed = 1;                     // --seed (every integrator)
  Sampler sampler = Sampler::sobol;      // --sampler (every integrator)
  int max_depth = KASHA_MAX_PATH_DEPTH;  // --max-depth (every integrator): the path-length guard
  unsigned long long memory = 0;  // --memory: the photon or light-vertex store, bytes (0: auto)
};

struct IntegratorOption;
// The options every integrator takes, declared once.
const std::vector<IntegratorOption>& common_options();

}  // namespace kasha
