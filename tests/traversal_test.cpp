// The OpenCL traversal of the Embree-built BVH against Embree's own rtcIntersect1/rtcOccluded1 on
// the same rays: same primitive and distance, ties only where triangles share an edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "geometry/bvh.h"
#include "geometry/cl_traversal.h"
#include "geometry/embree_scene.h"
#include "geometry/random_rays.h"
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

Agreement compare_closest(const Scene& scene, std::uint64_t seed) {
  FlatBvh bvh = build_bvh(scene.triangles);
  EXPECT_LE(bvh.depth, KASHA_BVH_MAX_DEPTH);
  EmbreeScene embree(scene.triangles);
  ClTraversal traversal(device(), bvh);
  std::vector<KRay> rays = random_rays(scene.triangles, kRays, seed);
  std::vector<KHit> expected;
  embree.intersect_all(rays, expected);
  std::vector<KHit> got = traversal.closest(rays);
  const double extent = scene_extent(scene.triangles);

  Agreement a;
  for (size_t i = 0; i < rays.size(); ++i) {
    const KHit &e = expected[i], &g = got[i];
    if (e.prim >= 0) ++a.hits;
    // Float rounding in t grows with the distance and with the coordinates' magnitude.
    double tol = 1e-5 * (e.prim >= 0 ? e.t : g.t) + 1e-6 * extent;
    if (e.prim == g.prim) {
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
    } else if ((e.prim < 0 ? edge_distance(g) : edge_distance(e)) < 1e-5f) {
      ++a.edge_ties;  // grazes an edge: one watertight test counts it, the other does not
      continue;
    }
    ++a.mismatches;
    if (a.mismatches <= 5)
      ADD_FAILURE() << "ray " << i << ": Embree prim " << e.prim << " t " << e.t << ", OpenCL prim "
                    << g.prim << " t " << g.t;
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

void expect_agreement(const Scene& scene, std::uint64_t seed) {
  Agreement a = compare_closest(scene, seed);
  EXPECT_EQ(a.mismatches, 0u);
  EXPECT_GT(a.hits, kRays / 4);          // the rays do exercise the geometry
  EXPECT_LT(a.edge_ties, kRays / 1000);  // ties stay rare
  EXPECT_EQ(a.same + a.edge_ties + a.coincident + a.mismatches, kRays);
  std::printf("  %zu rays, %zu hits, %zu identical, %zu edge ties, %zu on coincident faces\n",
              kRays, a.hits, a.same, a.edge_ties, a.coincident);
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
  std::vector<KTriangle> tris(2);
  float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0};  // collinear: zero area
  std::copy(a, a + 3, tris[0].v0), std::copy(b, b + 3, tris[0].v1), std::copy(c, c + 3, tris[0].v2);
  float d[3] = {0, 0, 1}, e[3] = {1, 0, 1}, f[3] = {0, 1, 1};
  std::copy(d, d + 3, tris[1].v0), std::copy(e, e + 3, tris[1].v1), std::copy(f, f + 3, tris[1].v2);
  tris[0].prim = 0, tris[1].prim = 1;
  ClTraversal traversal(device(), build_bvh(tris));
  KRay r{
      {0.5f, 0.0f, -1.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};  // through the degenerate one first
  KRay s{{0.2f, 0.2f, -1.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
  std::vector<KHit> hits = traversal.closest({r, s});
  EXPECT_EQ(hits[0].prim, -1);
  EXPECT_EQ(hits[1].prim, 1);
  EXPECT_NEAR(hits[1].t, 2.0f, 1e-6f);
  for (float x : {hits[0].t, hits[1].t, hits[1].u, hits[1].v})
    EXPECT_TRUE(std::isfinite(x) || x == INFINITY);
}
