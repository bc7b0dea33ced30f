#include "study/image_regions.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "study/primary_rays.h"

namespace kasha {

std::vector<ShapeRegion> shape_regions(const Scene& scene, const Camera& camera, double margin_px) {
  std::vector<int> shape_of(scene.triangles.size(), -1);
  for (size_t s = 0; s < scene.shapes.size(); ++s)
    for (int t = 0; t < scene.shapes[s].triangle_count; ++t)
      shape_of[scene.shapes[s].first_triangle + t] = static_cast<int>(s);
  const PrimaryRays rays(scene, camera);
  // The shape seen through image point (px, py) in pixels from the top-left corner; -1 for none.
  auto seen = [&](double px, double py) {
    const int t = rays.triangle(px, py);
    return t < 0 ? -1 : shape_of[t];
  };
  std::map<int, ShapeRegion> regions;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const int shape = seen(cx, cy);
      bool inside = shape >= 0;
      for (int dy = -1; dy <= 1 && inside && margin_px > 0; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx)
          inside = seen(cx + dx * margin_px, cy + dy * margin_px) == shape;
      if (!inside) continue;
      regions[shape].shape = shape;
      regions[shape].pixels.push_back(static_cast<size_t>(y) * camera.width + x);
    }
  std::vector<ShapeRegion> out;
  for (auto& [shape, region] : regions) out.push_back(std::move(region));
  return out;
}

RegionXyz region_xyz(const Image& image, const std::vector<size_t>& pixels) {
  RegionXyz r;
  const double n = static_cast<double>(pixels.size());
  for (int c = 0; c < 3; ++c) {
    double sum = 0, sum2 = 0;
    for (size_t p : pixels) {
      const double v = image.xyz[3 * p + c];
      sum += v;
      sum2 += v * v;
    }
    r.mean[c] = n > 0 ? sum / n : 0;
    r.standard_error[c] =
        n > 1 ? std::sqrt(std::max(0.0, sum2 / n - r.mean[c] * r.mean[c]) / (n - 1)) : 0;
  }
  return r;
}

}  // namespace kasha
