#pragma once
// The --max-depth cap a render uses: pbrt-v4's maxdepth, the most scattering vertices (those
// other than the camera's and the light's; a fluorescent, gloss or delta bounce is one) a light
// path may have and still count. The kernels take it as KASHA_DEPTH_CAP, defined only when there
// is a cap, so an uncapped render's kernels are the unbiased ones.
#include <string>

#include "render/render_settings.h"
#include "scene/scene.h"

namespace kasha {

// The cap, or IntegratorSettings::kNoDepthCap; `--max-depth scene` takes the scene's own, and
// throws an Error (depth_cap_refusal) where the scene names none.
int depth_cap(const IntegratorSettings& settings, const Scene& scene);

// Why `--max-depth scene` cannot be used with `scene`, "" where it can: the one-line usage error
// `--max-depth: scene: FILE names no maxdepth ...`.
std::string depth_cap_refusal(const IntegratorSettings& settings, const Scene& scene);

}  // namespace kasha
