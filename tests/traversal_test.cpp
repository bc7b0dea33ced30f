// The OpenCL traversal of the Embree-built BVH against Embree's own rtcIntersect1/rtcOccluded1 on
// the same rays: same primitive and distance, ties only where triangles share an edge.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "geometry/bvh.h"
#include "geometry/cl_traversal.h"
#include "geometry/embree_scene.h"
#include "geometry/instanced_bvh.h"
#include "geometry/random_rays.h"
#include "instanced_scene.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;

namespace {

constexpr size_t kRays = 120000;

ClContext& device() {
  static ClContext context(0);
  return context;
}

// Barycentric distance of a hit from its triangle's nearest edge.
float edge_distance(const KHit& h) {
  return std::min({h.u, h.v, 1.0f - h.u - h.v});
}

// |cos| of the angle between a ray and the triangle it hit: near 0 the ray runs along the face,
// where t and the barycentrics are ill-conditioned and two tests may round either way.
double incidence(const std::vector<KTriangle>& triangles, const KHit& h, const KRay& ray,
                 const std::vector<KInstance>& instances = {}) {
  const KTriangle t = instances.empty()
                          ? triangles.at(h.prim)
                          : placed_triangle(triangles.at(h.prim), instances.at(h.instance));
  Eigen::Vector3d a(t.v1[0] - t.v0[0], t.v1[1] - t.v0[1], t.v1[2] - t.v0[2]);
  Eigen::Vector3d b(t.v2[0] - t.v0[0], t.v2[1] - t.v0[1], t.v2[2] - t.v0[2]);
  Eigen::Vector3d d(ray.dir[0], ray.dir[1], ray.dir[2]);
  return std::abs(a.cross(b).normalized().dot(d.normalized()));
}

double scene_extent(const std::vector<KTriangle>& tris) {
  float lo = INFINITY, hi = -INFINITY;
  for (const KTriangle& t : tris)
    for (const float* v : {t.v0, t.v1, t.v2})
      for (int k = 0; k < 3; ++k) lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
  return hi - lo;
}

struct Agreement {
  size_t hits = 0, same = 0, edge_ties = 0, coincident = 0, mismatches = 0;
};

// Closest hits against Embree's. A hit within `edge_tol` (barycentric) of an edge, or nearly
// along its face, may be counted by one test and not the other.
Agreement compare_closest(const std::vector<KTriangle>& triangles, const std::vector<KRay>& rays,
                          float edge_tol = 1e-5f,
                          const SceneInstances& instances = SceneInstances()) {
  FlatBvh bvh = build_instanced_bvh(triangles, instances);
  EXPECT_LE(bvh.depth, KASHA_BVH_MAX_DEPTH);
  EmbreeScene embree(triangles, AlphaCutouts(), instances);
  const std::vector<KInstance>& placed = bvh.instances;
  ClTraversal traversal(device(), bvh);
  std::vector<KHit> expected;
  embree.intersect_all(rays, expected);
  std::vector<KHit> got = traversal.closest(rays);
  const double extent = scene_extent(triangles);

  Agreement a;
  for (size_t i = 0; i < rays.size(); ++i) {
    const KHit &e = expected[i], &g = got[i];
    if (e.prim >= 0) ++a.hits;
    // Float rounding in t grows with the distance and with the coordinates' magnitude.
    double tol = 1e-5 * (e.prim >= 0 ? e.t : g.t) + 1e-6 * extent;
    if (e.prim == g.prim && e.instance == g.instance) {
      if (e.prim < 0 || std::abs(e.t - g.t) <= tol) {
        ++a.same;
        continue;
      }
    } else if (e.prim >= 0 && g.prim >= 0 && std::abs(e.t - g.t) <= tol) {
      // Each side found its own triangle at the same distance: an edge two triangles share, or
      // coincident faces (a box standing on a floor). Either is a correct closest hit.
      if (std::min(edge_distance(e), edge_distance(g)) < 1e-4f)
        ++a.edge_ties;
      else
        ++a.coincident;
      continue;
    }
    // The nearer hit (a miss is the farthest) grazes an edge or its face: one test counts it, the
    // other does not, or rounds t differently.
    const KHit& nearer = g.prim < 0 || (e.prim >= 0 && e.t <= g.t) ? e : g;
    if (nearer.prim >= 0 && (edge_distance(nearer) < edge_tol ||
                             incidence(triangles, nearer, rays[i], placed) < 1e-2)) {
      ++a.edge_ties;
      continue;
    }
    ++a.mismatches;
    auto cosine = [&](const KHit& h) {
      return h.prim < 0 ? 0.0 : incidence(triangles, h, rays[i], placed);
    };
    if (a.mismatches <= 5)
      ADD_FAILURE() << "ray " << i << ": Embree prim " << e.prim << " (instance " << e.instance
                    << ") t " << e.t << " edge " << edge_distance(e) << " cos " << cosine(e)
                    << ", OpenCL prim " << g.prim << " (instance " << g.instance << ")"
                    << " t " << g.t << " edge " << edge_distance(g) << " cos " << cosine(g);
  }
  return a;
}

Scene scaled_scene(double scale) {
  // A closed inward box around an OBJ torus and a sphere: many rays start inside closed shapes.
  std::string s = std::to_string(scale);
  std::string torus = test::source_path("scenes/meshes/torus.obj");
  return load_scene(test::write_file("scaled.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]},
    "materials": {"m": {"passive": {"reflectance": 0.5}}},
    "shapes": [
      {"type": "box", "min": [-2, -2, -2], "max": [2, 2, 2], "material": "m", "inward": true,
       "transform": {"scale": )" + s + R"(}},
      {"type": "obj", "file": ")" + torus + R"(", "material": "m",
       "transform": {"scale": )" + s + R"(, "rotate": {"axis": [1, 1, 0], "deg": 30}}},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "m", "segments": 24,
       "transform": {"scale": )" + s + R"(}}]})"));
}

Agreement compare_closest(const Scene& scene, std::uint64_t seed) {
  return compare_closest(scene.triangles, random_rays(scene.triangles, kRays, seed));
}

void print(const Agreement& a, size_t rays) {
  std::printf("  %zu rays, %zu hits, %zu identical, %zu edge ties, %zu on coincident faces\n", rays,
              a.hits, a.same, a.edge_ties, a.coincident);
}

void expect_agreement(const Scene& scene, std::uint64_t seed) {
  Agreement a = compare_closest(scene, seed);
  EXPECT_EQ(a.mismatches, 0u);
  EXPECT_GT(a.hits, kRays / 4);          // the rays do exercise the geometry
  EXPECT_LT(a.edge_ties, kRays / 1000);  // ties stay rare
  EXPECT_EQ(a.same + a.edge_ties + a.coincident + a.mismatches, kRays);
  print(a, kRays);
}

// Occlusion answers that differ from Embree's, leaving out segments whose first hit (Embree's
// closest on the same interval) grazes an edge or ends within rounding of tmax.
size_t occluded_mismatches(const std::vector<KTriangle>& triangles, const std::vector<KRay>& rays,
                           size_t* blocked) {
  EmbreeScene embree(triangles);
  ClTraversal traversal(device(), build_bvh(triangles));
  std::vector<KHit> closest;
  embree.intersect_all(rays, closest);
  std::vector<int> got = traversal.occluded(rays);
  std::vector<KHit> cl_closest = traversal.closest(rays);
  size_t mismatches = 0;
  *blocked = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    bool expected = embree.occluded(rays[i]);
    *blocked += expected;
    if (expected == static_cast<bool>(got[i])) continue;
    // The hit the "blocked" side found: a graze of an edge or face, or within rounding of tmax.
    const KHit& h = expected ? closest[i] : cl_closest[i];
    bool tie = h.prim >= 0 && (edge_distance(h) < 1e-5f || h.t > rays[i].tmax * (1 - 1e-4f) ||
                               incidence(triangles, h, rays[i]) < 1e-2);
    if (!tie && ++mismatches <= 5)
      ADD_FAILURE() << "segment " << i << ": Embree " << expected << ", OpenCL " << got[i]
                    << "; Embree's closest prim " << h.prim << " t " << h.t << " (tmin "
                    << rays[i].tmin << ", tmax " << rays[i].tmax << ", edge " << edge_distance(h)
                    << "); OpenCL's prim " << cl_closest[i].prim << " t " << cl_closest[i].t
                    << " edge " << edge_distance(cl_closest[i]);
  }
  return mismatches;
}

// n triangles of random sizes and orientations in the unit cube, some long and thin.
std::vector<KTriangle> random_triangles(size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<KTriangle> tris(n);
  for (size_t i = 0; i < n; ++i) {
    float c[3], size = 0.02f + 0.3f * unit(rng) * unit(rng);
    for (float& x : c) x = unit(rng);
    for (float* v : {tris[i].v0, tris[i].v1, tris[i].v2})
      for (int k = 0; k < 3; ++k) v[k] = c[k] + size * (unit(rng) - 0.5f);
    tris[i].material = 0, tris[i].emitter = -1, tris[i].prim = static_cast<int>(i);
  }
  return tris;
}

KTriangle make_triangle(const float a[3], const float b[3], const float c[3], int prim) {
  KTriangle t{};
  std::copy(a, a + 3, t.v0), std::copy(b, b + 3, t.v1), std::copy(c, c + 3, t.v2);
  t.emitter = -1, t.prim = prim;
  return t;
}

}  // namespace

TEST(Traversal, CornellBoxMatchesEmbree) {
  expect_agreement(load_scene(test::source_path("scenes/cornell_box.json")), 1);
}

TEST(Traversal, ObjMeshSceneMatchesEmbree) {
  expect_agreement(load_scene(test::source_path("scenes/torus.json")), 2);
}

TEST(Traversal, TinySceneMatchesEmbree) {
  expect_agreement(scaled_scene(1e-3), 3);
}

TEST(Traversal, UnitSceneMatchesEmbree) {
  expect_agreement(scaled_scene(1.0), 4);
}

TEST(Traversal, HugeSceneMatchesEmbree) {
  expect_agreement(scaled_scene(1e3), 5);
}

TEST(Traversal, AnyHitMatchesEmbreeOccluded) {
  Scene scene = scaled_scene(1.0);
  FlatBvh bvh = build_bvh(scene.triangles);
  EmbreeScene embree(scene.triangles);
  ClTraversal traversal(device(), bvh);
  std::vector<KRay> rays = random_rays(scene.triangles, kRays, 6);
  std::vector<KHit> closest;
  embree.intersect_all(rays, closest);
  // Shadow segments ending well before or well after the first hit, so the answer is not a tie.
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  size_t blocked = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    float t = closest[i].prim >= 0 ? closest[i].t : 10.0f;
    rays[i].tmax = u(rng) < 0.5f ? 0.99f * t : 1.01f * t;
  }
  std::vector<int> got = traversal.occluded(rays);
  size_t mismatches = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    bool expected = embree.occluded(rays[i]);
    blocked += expected;
    if (expected != static_cast<bool>(got[i]) && edge_distance(closest[i]) > 1e-5f) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(blocked, kRays / 4);
  EXPECT_LT(blocked, kRays);
}

TEST(Traversal, DegenerateTrianglesAreNeverHit) {
  const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0};  // collinear: zero area
  const float d[3] = {0, 0, 1}, e[3] = {1, 0, 1}, f[3] = {0, 1, 1};
  std::vector<KTriangle> tris = {make_triangle(a, b, c, 0), make_triangle(d, e, f, 1)};
  ClTraversal traversal(device(), build_bvh(tris));
  // Through the degenerate one, then past the other (y < 0 at z = 1); the second hits it.
  KRay r{{0.5f, 0.2f, -1.0f}, 0.0f, {0.0f, -0.2f, 1.0f}, INFINITY};
  KRay s{{0.2f, 0.2f, -1.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
  std::vector<KHit> hits = traversal.closest({r, s});
  EXPECT_EQ(hits[0].prim, -1);
  EXPECT_EQ(hits[1].prim, 1);
  EXPECT_NEAR(hits[1].t, 2.0f, 1e-6f);
  for (float x : {hits[0].t, hits[1].t, hits[1].u, hits[1].v})
    EXPECT_TRUE(std::isfinite(x) || x == INFINITY);
  EXPECT_EQ(traversal.occluded({r, s}), (std::vector<int>{0, 1}));
}

// The flattened layout: every triangle in exactly one leaf slot, in leaf order, with its
// precomputed edges; each slot's box holds what hangs below it; unused slots empty.
TEST(Traversal, BvhLayoutHoldsEveryTriangleOnce) {
  for (size_t n : {size_t(1), size_t(7), size_t(9), size_t(65), size_t(5000)}) {
    SCOPED_TRACE(n);
    std::vector<KTriangle> in = random_triangles(n, n);
    FlatBvh bvh = build_bvh(in);
    ASSERT_EQ(bvh.triangles.size(), n);
    std::vector<int> seen(n, 0);
    size_t slots = 0, unused_slots = 0;
    // Walks the subtree `ref` and checks that every vertex below it lies in `box` (6 floats).
    std::function<void(int, const float*)> walk = [&](int ref, const float* box) {
      auto inside = [&](const float* v) {
        for (int k = 0; k < 3; ++k)
          if (!(v[k] >= box[2 * k] && v[k] <= box[2 * k + 1])) return false;
        return true;
      };
      if (ref < 0) {
        const KBvhLeaf& leaf = bvh.leaves.at(~ref);
        for (int i = 0; i < KASHA_BVH_LEAF_SIZE; ++i) {
          int t = leaf.tri[i];
          if (t < 0) {
            for (int k = 0; k < 3; ++k) EXPECT_TRUE(leaf.e1[k][i] == 0 && leaf.e2[k][i] == 0);
            continue;
          }
          ASSERT_LT(t, static_cast<int>(n));
          ++seen[t];
          const KTriangle& tri = bvh.triangles[t];
          EXPECT_EQ(in[tri.prim].v0[0], tri.v0[0]);
          for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(leaf.v0[k][i], tri.v0[k]);
            EXPECT_EQ(leaf.e1[k][i], tri.v1[k] - tri.v0[k]);
            EXPECT_EQ(leaf.e2[k][i], tri.v2[k] - tri.v0[k]);
          }
          EXPECT_TRUE(inside(tri.v0) && inside(tri.v1) && inside(tri.v2));
        }
        return;
      }
      const KBvhNode& node = bvh.nodes.at(ref);
      for (int i = 0; i < KASHA_BVH_WIDTH; ++i) {
        float child[6];
        for (int r = 0; r < 6; ++r) child[r] = node.bounds[r][i];
        ++slots;
        if (child[0] > child[1]) {  // unused: the empty box, all axes
          ++unused_slots;
          for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(child[2 * k], INFINITY);
            EXPECT_EQ(child[2 * k + 1], -INFINITY);
          }
          continue;
        }
        for (int k = 0; k < 3; ++k)
          EXPECT_TRUE(child[2 * k] >= box[2 * k] && child[2 * k + 1] <= box[2 * k + 1]);
        walk(node.child[i], child);
      }
    };
    const float all[6] = {-INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY};
    walk(0, all);
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "triangle " << i;
    if (n == 1) {
      EXPECT_EQ(unused_slots, static_cast<size_t>(KASHA_BVH_WIDTH - 1));
    }
    EXPECT_GT(slots, unused_slots);
  }
}

// Few triangles: a lone leaf under the root, nodes and leaves with most slots unused.
TEST(Traversal, SmallScenesMatchEmbree) {
  for (size_t n : {size_t(1), size_t(2), size_t(3), size_t(8), size_t(9), size_t(17), size_t(70)}) {
    SCOPED_TRACE(n);
    std::vector<KTriangle> tris = random_triangles(n, 100 + n);
    Agreement a = compare_closest(tris, random_rays(tris, 20000, n));
    EXPECT_EQ(a.mismatches, 0u);
    EXPECT_GT(a.hits, 0u);
    size_t blocked = 0;
    EXPECT_EQ(occluded_mismatches(tris, shadow_rays(tris, 20000, n), &blocked), 0u);
    EXPECT_GT(blocked, 0u);
  }
}

// Rays through shared edges and vertices of a mesh, and rays in the planes of the Cornell box's
// walls (direction components exactly zero, origins on a box face: 0·inf in the slab test).
TEST(Traversal, GrazingRaysMatchEmbree) {
  Scene scene = load_scene(test::source_path("scenes/cornell_box.json"));
  const std::vector<KTriangle>& tris = scene.triangles;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
  std::vector<KRay> rays;
  for (int i = 0; i < 20000; ++i) {
    // Toward a vertex or an edge's midpoint of a random triangle, from a random point.
    const KTriangle& t = tris[pick(rng)];
    float target[3];
    int kind = i % 4;
    for (int k = 0; k < 3; ++k)
      target[k] = kind == 0   ? t.v0[k]
                  : kind == 1 ? 0.5f * (t.v0[k] + t.v1[k])
                  : kind == 2 ? 0.5f * (t.v1[k] + t.v2[k])
                              : 0.5f * (t.v2[k] + t.v0[k]);
    KRay r{};
    float len = 0;
    for (int k = 0; k < 3; ++k) {
      r.org[k] = -1.2f + 2.4f * unit(rng) + (k == 1 ? 1.0f : 0.0f);
      r.dir[k] = target[k] - r.org[k];
      len += r.dir[k] * r.dir[k];
    }
    for (float& d : r.dir) d /= std::sqrt(len);
    r.tmin = 0.0f, r.tmax = INFINITY;
    rays.push_back(r);
  }
  for (int i = 0; i < 20000; ++i) {
    // Axis-aligned, in the plane of a wall (x = ±1, y = 0 or 2, z = -1) or of the box's faces.
    KRay r{};
    const float planes[5][2] = {{0, -1}, {0, 1}, {1, 0}, {1, 2}, {2, -1}};
    const float* p = planes[i % 5];
    int axis = static_cast<int>(p[0]), along = (axis + 1 + i / 5 % 2) % 3;
    for (int k = 0; k < 3; ++k) r.org[k] = -1.2f + 2.4f * unit(rng) + (k == 1 ? 1.0f : 0.0f);
    r.org[axis] = p[1];
    r.dir[along] = (i / 10) % 2 ? 1.0f : -1.0f;
    r.tmin = 0.0f, r.tmax = INFINITY;
    rays.push_back(r);
  }
  Agreement a = compare_closest(tris, rays, 1e-4f);
  print(a, rays.size());
  EXPECT_EQ(a.mismatches, 0u);
  EXPECT_GT(a.hits, rays.size() / 2);
}

// [tmin, tmax] cuts: intervals starting past the first surface and ending short of it.
TEST(Traversal, RayIntervalsMatchEmbree) {
  Scene scene = scaled_scene(1.0);
  std::vector<KRay> rays = random_rays(scene.triangles, kRays, 10);
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (KRay& r : rays) {
    r.tmin = 3.0f * unit(rng) * unit(rng);
    r.tmax = unit(rng) < 0.2f ? INFINITY : r.tmin + 4.0f * unit(rng);
  }
  Agreement a = compare_closest(scene.triangles, rays);
  print(a, rays.size());
  EXPECT_EQ(a.mismatches, 0u);
  EXPECT_GT(a.hits, kRays / 4);
  size_t blocked = 0;
  EXPECT_EQ(occluded_mismatches(scene.triangles, rays, &blocked), 0u);
  EXPECT_GT(blocked, kRays / 4);
  EXPECT_LT(blocked, kRays);
}

// The benchmark's shadow segments, toward points of the scene's triangles.
TEST(Traversal, ShadowSegmentsMatchEmbree) {
  for (const char* file : {"scenes/cornell_box.json", "scenes/torus.json"}) {
    SCOPED_TRACE(file);
    Scene scene = load_scene(test::source_path(file));
    size_t blocked = 0;
    EXPECT_EQ(
        occluded_mismatches(scene.triangles, shadow_rays(scene.triangles, kRays, 11), &blocked),
        0u);
    EXPECT_GT(blocked, kRays / 10);
    EXPECT_LT(blocked, kRays - kRays / 20);
  }
}

// Two levels: an object placed 9 times (rotated, scaled unevenly, mirrored) in a box, against
// Embree's own instances; rays over the placed geometry (the same scene written out flat).
TEST(Traversal, InstancedSceneMatchesEmbree) {
  const Scene scene = load_scene(test::instanced_scene(false));
  const Scene flat = load_scene(test::instanced_scene(true));
  ASSERT_EQ(scene.instances.placements.size(), 9u);
  const std::vector<KRay> rays = random_rays(flat.triangles, kRays, 7);
  Agreement a = compare_closest(scene.triangles, rays, 1e-5f, scene.instances);
  EXPECT_EQ(a.mismatches, 0u);
  EXPECT_GT(a.hits, kRays / 4);
  EXPECT_LT(a.edge_ties, kRays / 1000);
  print(a, kRays);

  // Shadow segments toward points of the placed triangles: blocked or not as Embree says.
  const std::vector<KRay> shadows = shadow_rays(flat.triangles, kRays / 4, 8);
  EmbreeScene embree(scene.triangles, AlphaCutouts(), scene.instances);
  ClTraversal traversal(device(), build_instanced_bvh(scene.triangles, scene.instances));
  const std::vector<int> got = traversal.occluded(shadows);
  size_t blocked = 0, differ = 0;
  for (size_t i = 0; i < shadows.size(); ++i) {
    const bool expected = embree.occluded(shadows[i]);
    blocked += expected;
    differ += expected != static_cast<bool>(got[i]);
  }
  EXPECT_LE(differ, shadows.size() / 2000);  // a segment grazing an edge may go either way
  EXPECT_GT(blocked, shadows.size() / 10);
  EXPECT_LT(blocked, shadows.size());
}
