#pragma once
// Reproducible random rays over a scene's bounds, for traversal tests and benchmarks: origins
// uniform in the (slightly enlarged) bounding box, so many start inside closed shapes, and
// directions uniform on the sphere.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

std::vector<KRay> random_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed);

// Shadow segments: from origins as above toward a uniform point of a random triangle, ending
// 0.1 % short of it (tmax < length, direction unit), so the target itself never counts and
// whether the segment is blocked depends on what lies between.
std::vector<KRay> shadow_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed);

}  // namespace kasha
