#include "integrators/vcm/merging_distance.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "integrators/vcm/camera_probe.h"

namespace kasha {

namespace {

using namespace camera_probe;

// A surface the camera path passes without a vertex that merges or connects: a smooth dielectric
// or conductor, or a material that is only an ideal mirror lobe.
bool delta_surface(const Material& m) {
  if (m.specular()) return !m.rough();
  return m.rho.empty() && !m.fluorescent() && !m.coat && m.gloss && m.gloss->mirror;
}

// Points on the emitters' fronts: the centroids of up to 64 of their triangles, evenly spread.
std::vector<const KTriangle*> emitter_points(const Scene& scene) {
  std::vector<const KTriangle*> all;
  for (const KTriangle& t : scene.triangles)
    if (t.emitter >= 0) all.push_back(&t);
  constexpr size_t kMost = 64;
  if (all.size() <= kMost) return all;
  std::vector<const KTriangle*> some;
  for (size_t i = 0; i < kMost; ++i) some.push_back(all[i * all.size() / kMost]);
  return some;
}

// Whether x (normal n, on the side the camera path came from: `side`) sees the front of one of
// the emitter points.
bool lit_directly(const EmbreeScene& embree, const std::vector<const KTriangle*>& lamps,
                  const Eigen::Vector3f& x, const Eigen::Vector3f& side) {
  for (const KTriangle* t : lamps) {
    const Eigen::Vector3f c = (vec(t->v0) + vec(t->v1) + vec(t->v2)) / 3, d = c - x;
    const float dist = d.norm();
    if (!(dist > 0) || d.dot(side) <= 0 || triangle_normal(*t).dot(d) >= 0) continue;
    KRay r{};
    const Eigen::Vector3f org = x + 1e-4f * std::max(1.0f, x.norm()) * side;
    for (int k = 0; k < 3; ++k) r.org[k] = org[k], r.dir[k] = d[k] / dist;
    r.tmax = dist * (1 - 1e-3f);
    if (!embree.occluded(r)) return true;
  }
  return false;
}

}  // namespace

MergingVertices probe_merging_vertices(const Scene& scene, const EmbreeScene& embree,
                                       const KCamera& camera) {
  constexpr int kGrid = 32, kMostBounces = 8;
  const std::vector<const KTriangle*> lamps = emitter_points(scene);
  std::vector<double> distances;
  int unlit = 0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const float sx = 2.0f * (x + 0.5f) / kGrid - 1, sy = 1 - 2.0f * (y + 0.5f) / kGrid;
      Eigen::Vector3f org = vec(camera.position), dir = camera_direction(camera, sx, sy);
      double travelled = 0;
      for (int bounce = 0; bounce < kMostBounces; ++bounce) {
        KRay r{};
        for (int c = 0; c < 3; ++c) r.org[c] = org[c], r.dir[c] = dir[c];
        r.tmax = INFINITY;
        const KHit h = embree.intersect(r);
        if (h.prim < 0) break;
        travelled += h.t;
        const KTriangle t = scene.hit_triangle(h);
        const Eigen::Vector3f n = triangle_normal(t);
        const bool through = t.material >= 0 && scene.materials[t.material].kind == MaterialKind::interface;
        if (!through && (t.material < 0 || !delta_surface(scene.materials[t.material]))) {
          distances.push_back(travelled);
          if (t.emitter < 0 && !lit_directly(embree, lamps, org + h.t * dir,
                                             n.dot(dir) < 0 ? n : Eigen::Vector3f(-n)))
            ++unlit;
          break;
        }
        org += h.t * dir;
        // An interface (a boundary of media) passes the ray on; a dielectric refracts it straight.
        if (!through && scene.materials[t.material].kind != MaterialKind::dielectric) dir -= 2 * n.dot(dir) * n;
        // Off the surface by a relative epsilon, on the side the path leaves by.
        org += (n.dot(dir) > 0 ? 1e-4f : -1e-4f) * std::max(1.0f, org.norm()) * n;
      }
    }
  MergingVertices m;
  if (distances.empty()) return m;
  if (scene.lights.empty()) m.unlit = static_cast<double>(unlit) / distances.size();
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  m.distance = distances[distances.size() / 2];
  return m;
}

}  // namespace kasha
