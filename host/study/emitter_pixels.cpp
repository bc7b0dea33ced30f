#include "study/emitter_pixels.h"

#include <cmath>

#include "geometry/embree_scene.h"

namespace kasha {

std::vector<bool> emitter_pixels(const Scene& scene) {
  EmbreeScene embree(scene.triangles);
  const KCamera k = scene.camera.to_kernel();
  const int w = scene.camera.width, h = scene.camera.height, n = 4;
  std::vector<bool> mask(static_cast<size_t>(w) * h, false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int j = 0; j < n * n && !mask[static_cast<size_t>(y) * w + x]; ++j) {
        float sx = 2.0f * (x + (j % n + 0.5f) / n) / w - 1,
              sy = 1 - 2.0f * (y + (j / n + 0.5f) / n) / h;
        KRay r{};
        for (int c = 0; c < 3; ++c)
          r.org[c] = k.position[c], r.dir[c] = k.forward[c] + sx * k.right[c] + sy * k.up[c];
        r.tmax = INFINITY;
        KHit hit = embree.intersect(r);
        if (hit.prim < 0) continue;
        const KTriangle& t = scene.triangles[hit.prim];
        if (t.emitter < 0) continue;
        float e1[3], e2[3], nrm[3];
        for (int c = 0; c < 3; ++c) e1[c] = t.v1[c] - t.v0[c], e2[c] = t.v2[c] - t.v0[c];
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (nrm[0] * r.dir[0] + nrm[1] * r.dir[1] + nrm[2] * r.dir[2] < 0)  // its front
          mask[static_cast<size_t>(y) * w + x] = true;
      }
  return mask;
}

}  // namespace kasha
