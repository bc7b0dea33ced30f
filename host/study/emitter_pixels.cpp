#include "study/emitter_pixels.h"

#include "study/primary_rays.h"

namespace kasha {

std::vector<bool> emitter_pixels(const Scene& scene) {
  const PrimaryRays rays(scene, scene.camera);
  const int w = scene.camera.width, h = scene.camera.height, n = 4;
  std::vector<bool> mask(static_cast<size_t>(w) * h, false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int j = 0; j < n * n && !mask[static_cast<size_t>(y) * w + x]; ++j) {
        bool front = false;
        const int t = rays.triangle(x + (j % n + 0.5) / n, y + (j / n + 0.5) / n, &front);
        if (t >= 0 && front && scene.triangles[t].emitter >= 0)
          mask[static_cast<size_t>(y) * w + x] = true;
      }
  return mask;
}

}  // namespace kasha
