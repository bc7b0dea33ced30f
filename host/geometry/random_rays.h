#pragma once
// Reproducible random rays over a scene's bounds, for traversal tests and benchmarks: origins
// uniform in the (slightly enlarged) bounding box, so many start inside closed shapes, and
// directions uniform on the sphere.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shared_types.h"

namespace kasha {

std::vector<KRay> random_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed);

}  // namespace kasha
