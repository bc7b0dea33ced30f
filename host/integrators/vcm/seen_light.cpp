#include "integrators/vcm/seen_light.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel_for.h"
#include "geometry/embree_scene.h"
#include "integrators/vcm/camera_probe.h"

namespace kasha {

namespace {

using namespace camera_probe;

// A ray still followed: where it starts, where it goes, its bounces so far.
struct Probe {
  Eigen::Vector3f org, dir;
  int bounces;
};

// A material with a delta lobe, which the probe follows: glass and metal, smooth; an ideal
// mirror lobe; a smooth coat.
bool has_delta_lobe(const Material& m) {
  if (m.specular()) return !m.rough();
  return (m.gloss && m.gloss->mirror) || (m.coat && !m.coat->rough());
}

// Whether a camera ray from `org` along `dir` reaches light through delta bounces alone.
bool reaches_light(const Scene& scene, const EmbreeScene& embree, bool infinite,
                   const Eigen::Vector3f& org, const Eigen::Vector3f& dir) {
  // Glass splits a probe in two at every hit: at most this many rays a probe, so nested glass
  // costs a bounded start-up (a missed edge costs variance only).
  constexpr int kMostBounces = 8, kMostRays = 32;
  std::vector<Probe> stack{{org, dir, 0}};
  for (int rays = 0; !stack.empty() && rays < kMostRays; ++rays) {
    const Probe p = stack.back();
    stack.pop_back();
    KRay r{};
    for (int c = 0; c < 3; ++c) r.org[c] = p.org[c], r.dir[c] = p.dir[c];
    r.tmax = INFINITY;
    const KHit h = embree.intersect(r);
    if (h.prim < 0) {
      if (infinite) return true;
      continue;
    }
    const KTriangle t = scene.hit_triangle(h);
    Eigen::Vector3f n = triangle_normal(t);
    const bool front = n.dot(p.dir) < 0;
    if (t.emitter >= 0 && front) return true;
    if (t.material < 0 || p.bounces == kMostBounces) continue;
    const Material& m = scene.materials[t.material];
    if (!has_delta_lobe(m) && m.kind != MaterialKind::interface) continue;
    const Eigen::Vector3f at = p.org + h.t * p.dir;
    if (!scene.normals.empty()) {
      // The shading normal the kernels bounce about (kernels/geometry/hit_point.h).
      const TriangleNormals& sn = scene.normals[h.prim];
      const Eigen::Vector3f s =
          scene.hit_normal(h, (1 - h.u - h.v) * sn[0] + h.u * sn[1] + h.v * sn[2]).cast<float>();
      if (s.norm() > 1e-6f) n = s.dot(n) < 0 ? -s.normalized() : s.normalized();
    }
    if (!front) n = -n;  // on the ray's side
    const float cos_i = -n.dot(p.dir);
    const float eps = 1e-4f * std::max(1.0f, at.norm());
    if (m.kind == MaterialKind::interface) {  // a boundary of media: straight on
      stack.push_back({at - eps * n, p.dir, p.bounces + 1});
      continue;
    }
    stack.push_back({at + eps * n, p.dir + 2 * cos_i * n, p.bounces + 1});
    if (m.kind == MaterialKind::dielectric) {
      // Snell's law into the far side (total internal reflection: the reflection alone).
      const float eta = front ? static_cast<float>(m.eta) : 1.0f / static_cast<float>(m.eta);
      const float sin2 = std::max(0.0f, 1 - cos_i * cos_i) / (eta * eta);
      if (sin2 < 1)
        stack.push_back(
            {at - eps * n, p.dir / eta + (cos_i / eta - std::sqrt(1 - sin2)) * n, p.bounces + 1});
    }
  }
  return false;
}

}  // namespace

std::vector<int> seen_light_pixels(const Scene& scene, const EmbreeScene& embree,
                                   const KCamera& camera) {
  const bool infinite = std::any_of(scene.lights.begin(), scene.lights.end(),
                                    [](const Light& l) { return l.type == LightType::infinite; });
  const int w = camera.width, h = camera.height;
  const Eigen::Vector3f org = vec(camera.position);
  // Per pixel, how many of its 2 × 2 probes reach light.
  std::vector<int> lit(static_cast<size_t>(w) * h, 0);
  parallel_for(lit.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const int px = static_cast<int>(i % w), py = static_cast<int>(i / w);
      for (int k = 0; k < 4; ++k) {
        const float sx = 2.0f * (px + 0.25f + 0.5f * (k & 1)) / w - 1,
                    sy = 1 - 2.0f * (py + 0.25f + 0.5f * (k >> 1)) / h;
        lit[i] += reaches_light(scene, embree, infinite, org, camera_direction(camera, sx, sy));
      }
    }
  });
  // An edge: the probes of the pixel and of those beside it disagree.
  std::vector<int> edge(lit.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool some = false, all = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || u >= w || v < 0 || v >= h) continue;
          const int n = lit[static_cast<size_t>(v) * w + u];
          some = some || n > 0;
          all = all && n == 4;
        }
      edge[static_cast<size_t>(y) * w + x] = some && !all;
    }
  return edge;
}

}  // namespace kasha
