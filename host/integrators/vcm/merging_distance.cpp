#include "integrators/vcm/merging_distance.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/embree_scene.h"

namespace kasha {

namespace {

// A surface the camera path passes without a vertex that merges or connects: a smooth dielectric
// or conductor, or a material that is only an ideal mirror lobe.
bool delta_surface(const Material& m) {
  if (m.specular()) return !m.rough();
  return m.rho.empty() && !m.fluorescent() && !m.coat && m.gloss && m.gloss->mirror;
}

Eigen::Vector3f vec(const float* v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

double merging_distance(const Scene& scene, const KCamera& camera) {
  const EmbreeScene embree(scene.triangles);
  constexpr int kGrid = 32, kMostBounces = 8;
  std::vector<double> distances;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const float sx = 2.0f * (x + 0.5f) / kGrid - 1, sy = 1 - 2.0f * (y + 0.5f) / kGrid;
      Eigen::Vector3f org = vec(camera.position),
                      dir = (vec(camera.forward) + sx * vec(camera.right) + sy * vec(camera.up))
                                .normalized();
      double travelled = 0;
      for (int bounce = 0; bounce < kMostBounces; ++bounce) {
        KRay r{};
        for (int c = 0; c < 3; ++c) r.org[c] = org[c], r.dir[c] = dir[c];
        r.tmax = INFINITY;
        const KHit h = embree.intersect(r);
        if (h.prim < 0) break;
        travelled += h.t;
        const KTriangle& t = scene.triangles[h.prim];
        if (t.material < 0 || !delta_surface(scene.materials[t.material])) {
          distances.push_back(travelled);
          break;
        }
        const Eigen::Vector3f n = (vec(t.v1) - vec(t.v0)).cross(vec(t.v2) - vec(t.v0)).normalized();
        org += h.t * dir;
        if (scene.materials[t.material].kind != MaterialKind::dielectric) dir -= 2 * n.dot(dir) * n;
        // Off the surface by a relative epsilon, on the side the path leaves by.
        org += (n.dot(dir) > 0 ? 1e-4f : -1e-4f) * std::max(1.0f, org.norm()) * n;
      }
    }
  if (distances.empty()) return 0;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return distances[distances.size() / 2];
}

}  // namespace kasha
