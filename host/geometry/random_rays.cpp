#include "geometry/random_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace kasha {

std::vector<KRay> random_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const KTriangle& t : triangles)
    for (const float* v : {t.v0, t.v1, t.v2})
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<KRay> rays(count);
  for (KRay& r : rays) {
    for (int k = 0; k < 3; ++k) {
      float extent = hi[k] - lo[k];
      r.org[k] = lo[k] - 0.1f * extent + 1.2f * extent * unit(rng);
    }
    float z = 1.0f - 2.0f * unit(rng), phi = 2.0f * static_cast<float>(M_PI) * unit(rng);
    float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    r.dir[0] = s * std::cos(phi), r.dir[1] = s * std::sin(phi), r.dir[2] = z;
    r.tmin = 0.0f;
    r.tmax = std::numeric_limits<float>::infinity();
  }
  return rays;
}

}  // namespace kasha
