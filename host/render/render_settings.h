#pragma once
// The render settings' values: every option an integrator or every integrator takes, as the
// command line fills them. Each integrator declares its own options beside its registration line
// (render/integrator_option.h); the options every integrator takes (--seed, --max-depth,
// --depth-guard, --sampler) are declared once, here. Enumerations are parsed once, into the enums
// below.
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
  unsigned seed = 1;                 // --seed (every integrator)
  Sampler sampler = Sampler::sobol;  // --sampler (every integrator)
  // --max-depth (every integrator): pbrt-v4's maxdepth, the scattering vertices a counted light
  // path may have (render/depth_cap.h); none by default, as an unbiased render needs;
  // kSceneDepthCap: `--max-depth scene`, the scene's own (Scene::max_depth).
  static constexpr int kNoDepthCap = -1;
  static constexpr int kSceneDepthCap = -2;
  int max_depth = kNoDepthCap;
  int depth_guard = KASHA_MAX_PATH_DEPTH;  // --depth-guard (every integrator): the safety guard
  unsigned long long memory = 0;  // --memory: the photon or light-vertex store, bytes (0: auto)
};

struct IntegratorOption;
// The options every integrator takes, declared once.
const std::vector<IntegratorOption>& common_options();

}  // namespace kasha
