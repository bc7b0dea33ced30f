#include "scene/medium_light_region.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace kasha {

// Whether triangle i is where the kernels place it: the scene's own, not an instanced object's
// (whose triangles are in object space).
static bool world_triangle(const Scene& scene, size_t i) {
  return scene.instances.empty() || i < static_cast<size_t>(scene.instances.world_triangles);
}

static Eigen::Vector3d vertex(const KTriangle& t, int k) {
  const float* v = k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
  return {v[0], v[1], v[2]};
}

// The distance along the ray o + t d (t > 0) to triangle t, Möller–Trumbore; infinity for a miss
// or a triangle the ray runs along.
static double ray_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const KTriangle& t) {
  const Eigen::Vector3d v0 = vertex(t, 0), e1 = vertex(t, 1) - v0, e2 = vertex(t, 2) - v0;
  const Eigen::Vector3d p = d.cross(e2);
  const double det = e1.dot(p);
  const double none = std::numeric_limits<double>::infinity();
  if (std::abs(det) < 1e-300) return none;
  const Eigen::Vector3d s = o - v0;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return none;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return none;
  const double dist = e2.dot(q) / det;
  return dist > 0 ? dist : none;
}

int outer_medium(const Scene& scene) {
  if (scene.triangle_media.empty()) return scene.camera_medium;
  // A ray from past every boundary along −x, aimed at the centre of the boundary triangle that
  // lies farthest along x: the first boundary it meets faces it with the outer medium's side.
  int aim = -1;
  double reach = -std::numeric_limits<double>::infinity(), far = reach;
  for (size_t i = 0; i < scene.triangle_media.size(); ++i) {
    if (!scene.triangle_media[i].transition() || !world_triangle(scene, i)) continue;
    const KTriangle& t = scene.triangles[i];
    const double centre = (vertex(t, 0).x() + vertex(t, 1).x() + vertex(t, 2).x()) / 3;
    if (centre > reach) reach = centre, aim = static_cast<int>(i);
    for (int k = 0; k < 3; ++k) far = std::max(far, vertex(t, k).x());
  }
  if (aim < 0) return scene.camera_medium;
  const KTriangle& target = scene.triangles[aim];
  const Eigen::Vector3d c = (vertex(target, 0) + vertex(target, 1) + vertex(target, 2)) / 3;
  const Eigen::Vector3d o(far + 1 + std::abs(far), c.y(), c.z()), d(-1, 0, 0);
  int hit = aim;
  double nearest = ray_distance(o, d, target);
  for (size_t i = 0; i < scene.triangle_media.size(); ++i) {
    if (!scene.triangle_media[i].transition() || !world_triangle(scene, i)) continue;
    const double t = ray_distance(o, d, scene.triangles[i]);
    if (t < nearest) nearest = t, hit = static_cast<int>(i);
  }
  const KTriangle& t = scene.triangles[hit];
  const Eigen::Vector3d n = (vertex(t, 1) - vertex(t, 0)).cross(vertex(t, 2) - vertex(t, 0));
  const MediumInterface& mi = scene.triangle_media[hit];
  // Arriving against the front (n · d < 0), the ray came from the outside.
  return n.dot(d) < 0 ? mi.outside : mi.inside;
}

// The box of the triangles with medium m on a side; an instanced object's with m on a side make
// it the scene's bounding cube. False: none has.
static bool boundary_box(const Scene& scene, int m, Eigen::AlignedBox3d& box) {
  for (size_t i = 0; i < scene.triangle_media.size(); ++i) {
    const MediumInterface& mi = scene.triangle_media[i];
    if (mi.inside != m && mi.outside != m) continue;
    if (!world_triangle(scene, i)) {
      Eigen::Vector3d centre;
      double radius;
      scene.bounding_sphere(centre, radius);
      box = Eigen::AlignedBox3d(centre.array() - radius, centre.array() + radius);
      return true;
    }
    for (int k = 0; k < 3; ++k) box.extend(vertex(scene.triangles[i], k));
  }
  return !box.isEmpty();
}

// What scales a grid's emission, as the means over its samples of its density, its emission
// scale and whether the temperature is above pbrt-v4's cutoff, multiplied: each is interpolated
// on its own, so the product is 0 only where one of them is 0 at every sample — where the grid
// emits nothing anywhere (a product per sample could be 0 while the interpolated ones are not).
static double grid_emission_mean(const Medium& medium) {
  const DensityGrid& g = *medium.grid;
  const auto mean = [](const std::vector<float>& v, const std::function<double(float)>& f) {
    double sum = 0;
    for (float x : v) sum += f(x);
    return v.empty() ? 1.0 : sum / static_cast<double>(v.size());
  };
  const auto same = [](float x) { return static_cast<double>(x); };
  double m = mean(g.values, same) * mean(g.emission_scale, same);
  if (medium.blackbody && !g.temperature.empty())
    m *= mean(g.temperature, [&](float t) {
      return (t - medium.blackbody->offset) * medium.blackbody->scale > 100 ? 1.0 : 0.0;
    });
  return m;
}

std::optional<MediumLightRegion> medium_light_region(const Scene& scene, int m) {
  const Medium& medium = scene.media[m];
  MediumLightRegion r;
  if (medium.emission.empty()) return r;
  r.outer = outer_medium(scene) == m;
  double mean = 1;
  if (medium.grid) {
    const DensityGrid& g = *medium.grid;
    const Eigen::Vector3d extent = g.p1 - g.p0;
    r.from_unit = g.to_world * Eigen::Translation3d(g.p0) * Eigen::Scaling(extent);
    r.volume = std::abs(g.to_world.linear().determinant()) * extent.prod();
    mean = grid_emission_mean(medium);
  } else {
    Eigen::AlignedBox3d box;
    if (r.outer || !boundary_box(scene, m, box)) return std::nullopt;
    // A little wider, so float rounding in the kernels cannot cut the region's faces.
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(1e-4 * box.diagonal().maxCoeff());
    box.extend(box.min() - pad).extend(box.max() + pad);
    r.from_unit = Eigen::Translation3d(box.min()) * Eigen::Scaling(Eigen::Vector3d(box.sizes()));
    r.volume = box.sizes().prod();
  }
  double emitted = 0;
  for (double e : medium.emission) emitted += e * scene.grid.bin_nm;
  r.power = 4 * M_PI * r.volume * mean * emitted;
  if (!(r.power > 0) || !std::isfinite(r.power)) r.power = 0;
  return r;
}

}  // namespace kasha
