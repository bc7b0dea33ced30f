#include "render/render_settings.h"

#include "render/integrator_option.h"

namespace kasha {

const std::vector<IntegratorOption>& common_options() {
  using V = IntegratorOption::Value;
  const IntegratorSettings defaults;
  // clang-format off: a table, an option a row
  static const std::vector<IntegratorOption> options = {
      {"--seed", V::integer, 0, 4294967295.0, "random seed", std::to_string(defaults.seed),
       KASHA_SETTING(seed)},
      {"--max-depth", V::depth_cap, 0, 1 << 30,
       "pbrt-v4's maxdepth, a biased cap: only light paths of at most N scattering vertices count "
       "(0: emitters seen directly, 1: direct light); scene: the pbrt-v4 scene's Integrator "
       "maxdepth",
       "none", KASHA_SETTING(max_depth)},
      {"--depth-guard", V::integer, 1, 1 << 30,
       "safety limit on path length in vertices, far beyond what Russian roulette reaches; what it "
       "cuts is reported",
       std::to_string(defaults.depth_guard), KASHA_SETTING(depth_guard)},
      {"--sampler", V::choice, 0, 0,
       "sobol (Owen-scrambled Sobol points) or independent (PCG streams)",
       choice_name(defaults.sampler), KASHA_SETTING(sampler)},
  };
  // clang-format on
  return options;
}

}  // namespace kasha
