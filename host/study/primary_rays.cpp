#include "study/primary_rays.h"

#include <cmath>

namespace kasha {

PrimaryRays::PrimaryRays(const Scene& scene, const Camera& camera)
    : scene_(scene),
      embree_(scene.triangles, AlphaCutouts(), scene.instances),
      camera_(camera.to_kernel()),
      width_(camera.width),
      height_(camera.height) {}

int PrimaryRays::triangle(double px, double py, bool* front) const {
  const float sx = static_cast<float>(2 * px / width_ - 1),
              sy = static_cast<float>(1 - 2 * py / height_);
  KRay r{};
  for (int c = 0; c < 3; ++c) {
    r.org[c] = camera_.position[c];
    r.dir[c] = camera_.forward[c] + sx * camera_.right[c] + sy * camera_.up[c];
  }
  r.tmax = INFINITY;
  const KHit h = embree_.intersect(r);
  if (h.prim >= 0 && front) {
    const KTriangle t = scene_.hit_triangle(h);
    float e1[3], e2[3];
    for (int c = 0; c < 3; ++c) e1[c] = t.v1[c] - t.v0[c], e2[c] = t.v2[c] - t.v0[c];
    const float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0]};
    *front = n[0] * r.dir[0] + n[1] * r.dir[1] + n[2] * r.dir[2] < 0;
  }
  return h.prim;
}

}  // namespace kasha
