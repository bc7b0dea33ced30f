#pragma once
// The light BVH next-event estimation picks an emitting triangle with (kernels/lights/light_bvh.h):
// pbrt-v4's BVHLightSampler, built over the emitting triangles by its modified surface area
// heuristic.
#include <cstdint>
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

struct LightBvh {
  std::vector<KLightNode> nodes;      // depth first: an interior node's first child follows it
  std::vector<std::uint64_t> trails;  // per emitting triangle, its path from the root
  int depth = 0;                      // levels below the root
};

// The tree over emitting triangles `emitting` (indices into `tris`, leaf order) of powers
// `power` (> 0); trails follow `emitting`'s order. Empty without emitting triangles. `spheres`
// (empty, or one per emitting triangle): the triangles of one sphere light (equal records of
// radius > 0) are one leaf, as pbrt-v4's sphere is one light, its first triangle standing for
// it; all of them share its trail.
LightBvh build_light_bvh(const std::vector<KTriangle>& tris, const std::vector<int>& emitting,
                         const std::vector<double>& power,
                         const std::vector<KSphereLight>& spheres = {});

}  // namespace kasha
