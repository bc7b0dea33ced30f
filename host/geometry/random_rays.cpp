#include "geometry/random_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace kasha {

namespace {

struct Bounds {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  explicit Bounds(const std::vector<KTriangle>& triangles) {
    for (const KTriangle& t : triangles)
      for (const float* v : {t.v0, t.v1, t.v2})
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  }
  // A uniform point of the box enlarged by 10 % of its extent on each side.
  template <typename Rng>
  void origin(Rng& rng, std::uniform_real_distribution<float>& unit, float out[3]) const {
    for (int k = 0; k < 3; ++k) {
      float extent = hi[k] - lo[k];
      out[k] = lo[k] - 0.1f * extent + 1.2f * extent * unit(rng);
    }
  }
};

}  // namespace

std::vector<KRay> random_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed) {
  const Bounds bounds(triangles);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<KRay> rays(count);
  for (KRay& r : rays) {
    bounds.origin(rng, unit, r.org);
    float z = 1.0f - 2.0f * unit(rng), phi = 2.0f * static_cast<float>(M_PI) * unit(rng);
    float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    r.dir[0] = s * std::cos(phi), r.dir[1] = s * std::sin(phi), r.dir[2] = z;
    r.tmin = 0.0f;
    r.tmax = std::numeric_limits<float>::infinity();
  }
  return rays;
}

std::vector<KRay> shadow_rays(const std::vector<KTriangle>& triangles, size_t count,
                              std::uint64_t seed) {
  const Bounds bounds(triangles);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<size_t> pick(0, triangles.size() - 1);
  std::vector<KRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    KRay r;
    bounds.origin(rng, unit, r.org);
    const KTriangle& t = triangles[pick(rng)];
    float a = unit(rng), b = unit(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    double d[3], length = 0;
    for (int k = 0; k < 3; ++k) {
      double target = t.v0[k] + a * (t.v1[k] - t.v0[k]) + b * (t.v2[k] - t.v0[k]);
      d[k] = target - r.org[k];
      length += d[k] * d[k];
    }
    length = std::sqrt(length);
    if (!(length > 0)) continue;
    for (int k = 0; k < 3; ++k) r.dir[k] = static_cast<float>(d[k] / length);
    r.tmin = 0.0f;
    r.tmax = static_cast<float>(0.999 * length);
    rays.push_back(r);
  }
  return rays;
}

}  // namespace kasha
