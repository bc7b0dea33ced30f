#pragma once
// pbrt-v4's Integrator statement: kasha's command line chooses the integrator and its samples, so
// only its maxdepth is kept, for `--max-depth scene` (render/depth_cap.h).
#include <optional>
#include <string>

#include "scene/pbrt/pbrt_parameters.h"

namespace kasha {

// pbrt-v4's default when a file has no Integrator statement: "volpath", whose maxdepth is 5.
constexpr int kPbrtDefaultMaxDepth = 5;

// The maxdepth of `Integrator "type" ...` as pbrt-v4's Create reads it (5 where not given), or
// none for an integrator that has none (ambientocclusion, function) or a negative one (no cap).
// Warns once, at `where`, that the statement is ignored and what `--max-depth scene` uses.
std::optional<int> pbrt_integrator_max_depth(const std::string& type, const PbrtParameters& params,
                                             const PbrtLocation& where);

}  // namespace kasha
