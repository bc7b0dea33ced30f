#include "integrators/photon/disc_coverage.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "integrators/photon/photon_gather.h"
#include "photon_layout.h"

namespace kasha {

namespace {
constexpr int kRings = 4, kPerRing = 4;  // 16 probes at equal-area radii
}

std::vector<float> disc_coverage(const EmbreeScene& scene, const float* vps, int vp_floats,
                                 size_t pixels, const std::vector<double>& radius, float rotation) {
  std::vector<float> coverage(pixels, 1.0f);
  auto work = [&](size_t begin, size_t end) {
    for (size_t px = begin; px < end; ++px) {
      const float* vp = vps + px * vp_floats;
      if (vp[KASHA_VP_VALID] == 0.0f) continue;
      const float r = static_cast<float>(radius[px]);
      const float n[3] = {vp[3], vp[4], vp[5]};
      // A tangent basis (s, t) around n.
      float sign = n[2] >= 0 ? 1.0f : -1.0f, a = -1.0f / (sign + n[2]), b = n[0] * n[1] * a;
      const float s[3] = {1.0f + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
      const float t[3] = {b, sign + n[1] * n[1] * a, -n[1]};
      int covered = 0;
      for (int ring = 0; ring < kRings; ++ring)
        for (int k = 0; k < kPerRing; ++k) {
          float rho = r * std::sqrt((ring + 0.5f) / kRings);
          float phi =
              rotation + 2.0f * static_cast<float>(M_PI) * (k + 0.5f * (ring % 2)) / kPerRing;
          float du = rho * std::cos(phi), dv = rho * std::sin(phi);
          // Through the gather's slab around the tangent plane, along the normal: any surface the
          // gather would accept there (facing the same way) covers the point.
          const float h = kGatherSlab * r;
          KRay ray{};
          for (int c = 0; c < 3; ++c) {
            ray.org[c] = vp[c] + du * s[c] + dv * t[c] + h * n[c];
            ray.dir[c] = -n[c];
          }
          ray.tmin = 0.0f;
          ray.tmax = 2.0f * h;
          KHit hit = scene.intersect(ray);
          if (hit.prim < 0) continue;
          if (scene.facing_normal_dot(hit.prim, ray.dir, n) > 0.5f) ++covered;
        }
      coverage[px] = std::max(1, covered) / static_cast<float>(kRings * kPerRing);
    }
  };
  parallel_for(pixels, work);
  return coverage;
}

}  // namespace kasha
