#include "render/depth_cap.h"

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

std::string depth_cap_refusal(const IntegratorSettings& settings, const Scene& scene) {
  if (settings.max_depth != IntegratorSettings::kSceneDepthCap || scene.max_depth) return "";
  return "--max-depth: scene: " + printable(scene.file) +
         " names no maxdepth (a pbrt-v4 scene's Integrator gives it, 5 by default; a kasha "
         "scene's \"max_depth\"); give --max-depth N";
}

int depth_cap(const IntegratorSettings& settings, const Scene& scene) {
  if (settings.max_depth != IntegratorSettings::kSceneDepthCap) return settings.max_depth;
  const std::string refusal = depth_cap_refusal(settings, scene);
  if (!refusal.empty()) throw Error(refusal);
  return *scene.max_depth;
}

}  // namespace kasha
