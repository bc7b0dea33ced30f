#include "render/light_bvh.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace kasha {
namespace {

using Eigen::Vector3d;

// pbrt-v4's DirectionCone: the directions within theta of w (its cosine kept too: the builder
// unites millions of cones, and an arccosine each would be most of its time).
struct Cone {
  Vector3d w = Vector3d::UnitZ();
  double cos_theta = 1, theta = 0;
};

// pbrt-v4's LightBounds of one-sided emitters (θe = π/2); empty while phi is 0.
struct Bounds {
  Vector3d lo = Vector3d::Constant(INFINITY), hi = Vector3d::Constant(-INFINITY);
  Cone cone;
  double phi = 0;
};

struct Item {
  Bounds bounds;
  Vector3d centroid;
  int tri;    // leaf order
  int index;  // among the emitting triangles
};

// pbrt-v4's AngleBetween, accurate near 0 and π.
double angle_between(const Vector3d& a, const Vector3d& b) {
  if (a.dot(b) < 0) return M_PI - 2 * std::asin(std::min(1.0, (a + b).norm() / 2));
  return 2 * std::asin(std::min(1.0, (b - a).norm() / 2));
}

// pbrt-v4's Union of direction cones. Adding a triangle's normal to a cone that holds it already
// is the common case: a dot product settles it.
Cone unite(const Cone& a, const Cone& b) {
  if (a.theta >= M_PI || (b.theta == 0 && a.w.dot(b.w) >= a.cos_theta)) return a;
  if (b.theta >= M_PI) return b;
  const double td = angle_between(a.w, b.w);
  if (std::min(td + b.theta, M_PI) <= a.theta) return a;
  if (std::min(td + a.theta, M_PI) <= b.theta) return b;
  const double to = (a.theta + td + b.theta) / 2;
  const Vector3d wr = a.w.cross(b.w);
  if (to >= M_PI || wr.squaredNorm() == 0) return {a.w, -1, M_PI};
  // a's axis turned towards b's by to − θa, about their common perpendicular.
  const double tr = to - a.theta;
  const Vector3d w = std::cos(tr) * a.w + std::sin(tr) * wr.normalized().cross(a.w);
  return {w.normalized(), std::cos(to), to};
}

Bounds unite(const Bounds& a, const Bounds& b) {
  if (a.phi == 0) return b;
  if (b.phi == 0) return a;
  return {a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi), unite(a.cone, b.cone), a.phi + b.phi};
}

// pbrt-v4's BVHLightSampler::EvaluateCost: power times the cone's measure of directions times the
// box's surface area, times how much longer the node is along its longest axis than along `dim`.
// With θe = π/2 its M_Ω = 2π(1 − cos θo) + π/2 (2 θw sin θo − cos(θo − 2 θw) − 2 θo sin θo + cos
// θo), θw = min(θo + π/2, π), takes the closed forms below (no cosine; an arccosine only past π/2).
double split_cost(const Bounds& b, const Vector3d& extent, int dim) {
  if (b.phi == 0) return 0;
  const double c = std::clamp(b.cone.cos_theta, -1.0, 1.0),
               so = std::sqrt(std::max(0.0, 1 - c * c));
  const double m_omega = 2 * M_PI * (1 - c) + (c >= 0 ? M_PI * M_PI / 2 * so + M_PI * c
                                                      : M_PI * so * (M_PI - b.cone.theta));
  const Vector3d d = b.hi - b.lo;
  const double area = 2 * (d.x() * d.y() + d.x() * d.z() + d.y() * d.z());
  return b.phi * m_omega * (extent.maxCoeff() / extent[dim]) * area;
}

constexpr int kBuckets = 12;

int bucket_of(const Item& item, const Vector3d& cmin, const Vector3d& cmax, int dim) {
  const int b =
      static_cast<int>(kBuckets * (item.centroid[dim] - cmin[dim]) / (cmax[dim] - cmin[dim]));
  return std::clamp(b, 0, kBuckets - 1);
}

// Per axis, the bounds of the triangles in each bucket. pbrt-v4 unites the triangles' cones one by
// one, where every normal just outside the cone so far costs trigonometry (most of them, along a
// tessellated lamp); here a bucket's cone is about its triangles' mean normal, as wide as the
// farthest one: it bounds them as well, and only steers the split.
struct Buckets {
  Bounds bounds[3][kBuckets];

  Buckets(const std::vector<Item>& items, int start, int end, const Vector3d& cmin,
          const Vector3d& cmax) {
    Vector3d sum[3][kBuckets];
    for (auto& row : sum)
      for (Vector3d& v : row) v.setZero();
    for (int dim = 0; dim < 3; ++dim) {
      if (!(cmax[dim] > cmin[dim])) continue;
      for (int i = start; i < end; ++i) {
        const int k = bucket_of(items[i], cmin, cmax, dim);
        Bounds& b = bounds[dim][k];
        b.lo = b.lo.cwiseMin(items[i].bounds.lo);
        b.hi = b.hi.cwiseMax(items[i].bounds.hi);
        b.phi += items[i].bounds.phi;
        sum[dim][k] += items[i].bounds.cone.w;
      }
      for (int k = 0; k < kBuckets; ++k) {
        Cone& c = bounds[dim][k].cone;
        if (sum[dim][k].squaredNorm() > 0) c.w = sum[dim][k].normalized();
      }
      for (int i = start; i < end; ++i) {
        Cone& c = bounds[dim][bucket_of(items[i], cmin, cmax, dim)].cone;
        // A sphere light's cone is the whole sphere of directions.
        const bool whole = items[i].bounds.cone.theta >= M_PI;
        c.cos_theta = std::min(c.cos_theta, whole ? -1.0 : c.w.dot(items[i].bounds.cone.w));
      }
      for (Bounds& b : bounds[dim])
        b.cone.theta = std::acos(std::clamp(b.cone.cos_theta, -1.0, 1.0));
    }
  }
};

// pbrt-v4's split of items [start, end): the bucket boundary of least cost along any axis (its
// loop skips the boundary after the first bucket, and so does this one); -1 where none costs
// anything or one side would be empty.
int sah_split(std::vector<Item>& items, int start, int end, const Vector3d& extent,
              const Vector3d& cmin, const Vector3d& cmax) {
  double min_cost = INFINITY;
  int best_bucket = -1, best_dim = -1;
  const Buckets buckets(items, start, end, cmin, cmax);
  for (int dim = 0; dim < 3; ++dim) {
    if (cmax[dim] == cmin[dim]) continue;
    const Bounds* bucket = buckets.bounds[dim];
    Bounds below[kBuckets], above[kBuckets];
    for (int i = 0; i < kBuckets; ++i) below[i] = unite(i > 0 ? below[i - 1] : Bounds{}, bucket[i]);
    for (int i = kBuckets - 1; i >= 0; --i)
      above[i] = unite(i + 1 < kBuckets ? above[i + 1] : Bounds{}, bucket[i]);
    for (int i = 1; i < kBuckets - 1; ++i) {
      const double cost = split_cost(below[i], extent, dim) + split_cost(above[i + 1], extent, dim);
      if (cost > 0 && cost < min_cost) min_cost = cost, best_bucket = i, best_dim = dim;
    }
  }
  if (best_dim < 0) return -1;
  const auto mid = std::partition(items.begin() + start, items.begin() + end, [&](const Item& it) {
    return bucket_of(it, cmin, cmax, best_dim) <= best_bucket;
  });
  const int m = static_cast<int>(mid - items.begin());
  return m == start || m == end ? -1 : m;
}

// Below this depth the heuristic splits; from it on, halves by count along the widest spread of
// centroids, so no trail outgrows its 64 bits (2^31 triangles need 31 more levels).
constexpr int kBalancedFrom = KASHA_LIGHT_BVH_MAX_DEPTH - 32;

// Fewer triangles than this are halved by count (the heuristic's bookkeeping per node would
// outweigh their partition by far: most nodes are small), more by the heuristic.
constexpr int kSahItems = 16;

class Builder {
 public:
  Builder(std::vector<Item>& items, double total, LightBvh& out)
      : items_(items), total_(total), out_(out) {}

  // The subtree over items [start, end) at `depth`, reached by `trail`: its node index is the
  // next free one; returns its bounds.
  Bounds build(int start, int end, std::uint64_t trail, int depth) {
    out_.depth = std::max(out_.depth, depth);
    const int at = static_cast<int>(out_.nodes.size());
    out_.nodes.emplace_back();
    if (end - start == 1) {
      out_.trails[items_[start].index] = trail;
      out_.nodes[at] = node(items_[start].bounds, ~items_[start].tri);
      return items_[start].bounds;
    }
    const int mid = split(start, end, depth);
    const Bounds first = build(start, mid, trail, depth + 1);
    const int second_at = static_cast<int>(out_.nodes.size());
    const Bounds b = unite(first, build(mid, end, trail | (std::uint64_t(1) << depth), depth + 1));
    out_.nodes[at] = node(b, second_at);
    return b;
  }

 private:
  int split(int start, int end, int depth) {
    // Two triangles: every split the heuristic may choose parts them, in either order.
    if (end - start == 2) return start + 1;
    Vector3d extent_lo = Vector3d::Constant(INFINITY), extent_hi = -extent_lo;
    Vector3d cmin = extent_lo, cmax = extent_hi;
    for (int i = start; i < end; ++i) {
      extent_lo = extent_lo.cwiseMin(items_[i].bounds.lo);
      extent_hi = extent_hi.cwiseMax(items_[i].bounds.hi);
      cmin = cmin.cwiseMin(items_[i].centroid);
      cmax = cmax.cwiseMax(items_[i].centroid);
    }
    if (depth < kBalancedFrom && end - start >= kSahItems) {
      const int m = sah_split(items_, start, end, extent_hi - extent_lo, cmin, cmax);
      if (m >= 0) return m;
    }
    // pbrt-v4 halves by count where the heuristic finds nothing; by centroid here.
    int dim;
    (cmax - cmin).maxCoeff(&dim);
    const int mid = (start + end) / 2;
    std::nth_element(
        items_.begin() + start, items_.begin() + mid, items_.begin() + end,
        [dim](const Item& a, const Item& b) { return a.centroid[dim] < b.centroid[dim]; });
    return mid;
  }

  // The kernel's node: floats, the power relative to all the triangles' (importance is only ever
  // compared, and so it stays within float's range whatever the lamps' units). The cone is
  // widened by a hair, so rounding never leaves a triangle's normal outside it.
  KLightNode node(const Bounds& b, int child) const {
    KLightNode n{};
    for (int c = 0; c < 3; ++c) {
      n.lo[c] = static_cast<float>(b.lo[c]);
      n.hi[c] = static_cast<float>(b.hi[c]);
      n.w[c] = static_cast<float>(b.cone.w[c]);
    }
    n.phi = static_cast<float>(b.phi / total_);
    n.cos_o =
        b.cone.cos_theta >= 1 ? 1.0f : static_cast<float>(std::max(-1.0, b.cone.cos_theta - 1e-6));
    n.child = child;
    return n;
  }

  std::vector<Item>& items_;
  double total_;
  LightBvh& out_;
};

// Per emitting triangle, the first emitting triangle of its sphere light (itself where it is of
// none), and the leaf items of the sphere lights, their powers summed.
std::vector<int> sphere_items(const std::vector<int>& emitting, const std::vector<double>& power,
                              const std::vector<KSphereLight>& spheres, std::vector<Item>& items) {
  std::vector<int> first(emitting.size());
  std::map<std::array<float, 4>, int> seen;  // a sphere's record: its item
  for (size_t j = 0; j < emitting.size(); ++j) {
    first[j] = static_cast<int>(j);
    if (spheres.empty() || !(spheres[j].radius > 0)) continue;
    const KSphereLight& l = spheres[j];
    const auto [at, fresh] = seen.try_emplace({l.centre[0], l.centre[1], l.centre[2], l.radius},
                                              static_cast<int>(items.size()));
    if (fresh) {
      Item it;
      const Vector3d c(l.centre[0], l.centre[1], l.centre[2]);
      it.bounds.lo = c - Vector3d::Constant(l.radius);
      it.bounds.hi = c + Vector3d::Constant(l.radius);
      it.bounds.cone = {Vector3d::UnitZ(), -1, M_PI};  // pbrt-v4's sphere: every direction
      it.centroid = c;
      it.tri = emitting[j];
      it.index = static_cast<int>(j);
      items.push_back(it);
    }
    items[at->second].bounds.phi += power[j];
    first[j] = items[at->second].index;
  }
  return first;
}

}  // namespace

LightBvh build_light_bvh(const std::vector<KTriangle>& tris, const std::vector<int>& emitting,
                         const std::vector<double>& power,
                         const std::vector<KSphereLight>& spheres) {
  LightBvh out;
  if (emitting.empty()) return out;
  std::vector<Item> items;
  items.reserve(emitting.size());
  const std::vector<int> first = sphere_items(emitting, power, spheres, items);
  double total = 0;
  for (size_t j = 0; j < emitting.size(); ++j) {
    total += power[j];
    if (first[j] != static_cast<int>(j) || (!spheres.empty() && spheres[j].radius > 0)) continue;
    const KTriangle& t = tris[emitting[j]];
    const Vector3d v0(t.v0[0], t.v0[1], t.v0[2]), v1(t.v1[0], t.v1[1], t.v1[2]),
        v2(t.v2[0], t.v2[1], t.v2[2]);
    Item it;
    it.bounds.lo = v0.cwiseMin(v1).cwiseMin(v2);
    it.bounds.hi = v0.cwiseMax(v1).cwiseMax(v2);
    it.bounds.cone.w = (v1 - v0).cross(v2 - v0).normalized();
    it.bounds.phi = power[j];
    it.centroid = (it.bounds.lo + it.bounds.hi) / 2;
    it.tri = emitting[j];
    it.index = static_cast<int>(j);
    items.push_back(it);
  }
  out.trails.resize(emitting.size());
  out.nodes.reserve(2 * items.size() - 1);
  Builder(items, total, out).build(0, static_cast<int>(items.size()), 0, 0);
  for (size_t j = 0; j < emitting.size(); ++j) out.trails[j] = out.trails[first[j]];
  return out;
}

}  // namespace kasha
