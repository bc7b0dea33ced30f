// The light BVH next-event estimation picks emitting triangles with (host/render/light_bvh.cpp,
// kernels/lights/light_bvh.h; pbrt-v4's BVHLightSampler): the tree's structure on the host, and
// on the device the probabilities it gives against pbrt-v4's importance in double, their sum,
// what sample_light_from reports against light_pdf_from, and a cluster facing away.
#include "render/light_bvh.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "chi2.h"
#include "kernel_harness.h"
#include "light_sample_kernel.h"
#include "light_tables.h"
#include "shared/shared_types.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

// Emitting triangles (every one of them, leaf order), each its own emitter, their powers.
struct Lamps {
  std::vector<KTriangle> tris;
  std::vector<int> emitting;
  std::vector<double> power;
  void add(const Vector3d& a, const Vector3d& b, const Vector3d& c, double radiance) {
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (!(area > 0)) return;
    const int k = static_cast<int>(tris.size());
    tris.push_back(triangle(a, b, c, k, k));
    emitting.push_back(k);
    power.push_back(M_PI * area * radiance);
  }
};

// A sphere lamp of `bands` latitude bands, twice as many longitudes, emitting outwards.
void add_sphere(Lamps& l, const Vector3d& centre, double r, int bands, double radiance) {
  auto at = [&](int i, int j) {
    const double t = M_PI * i / bands, p = M_PI * j / bands;
    return Vector3d(
        centre + r * Vector3d(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)));
  };
  for (int i = 0; i < bands; ++i)
    for (int j = 0; j < 2 * bands; ++j) {
      l.add(at(i, j), at(i + 1, j), at(i + 1, j + 1), radiance);
      l.add(at(i, j), at(i + 1, j + 1), at(i, j + 1), radiance);
    }
}

// A rectangle lamp corner + s·a + t·b, (s, t) in [0, 1]², cut into n × n squares, emitting
// along a × b.
void add_grid(Lamps& l, const Vector3d& corner, const Vector3d& a, const Vector3d& b, int n,
              double radiance) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vector3d p = corner + a * i / n + b * j / n, da = a / n, db = b / n;
      l.add(p, p + da, p + da + db, radiance);
      l.add(p, p + da + db, p + db, radiance);
    }
}

Vector3d normal_of(const KTriangle& t) {
  const Vector3d v0(t.v0[0], t.v0[1], t.v0[2]), v1(t.v1[0], t.v1[1], t.v1[2]),
      v2(t.v2[0], t.v2[1], t.v2[2]);
  return (v1 - v0).cross(v2 - v0).normalized();
}

// Every trail leads from the root to its own triangle, and every node on the way bounds it: its
// box holds the triangle, its cone the triangle's normal.
void expect_trails_lead_home(const Lamps& l, const LightBvh& bvh) {
  int wrong = 0, unbounded = 0;
  for (size_t j = 0; j < l.emitting.size(); ++j) {
    const KTriangle& t = l.tris[l.emitting[j]];
    const Vector3d n = normal_of(t);
    std::uint64_t trail = bvh.trails[j];
    int node = 0;
    for (int depth = 0;; ++depth) {
      const KLightNode& k = bvh.nodes[node];
      const Vector3d w(k.w[0], k.w[1], k.w[2]);
      bool inside = w.normalized().dot(n) >= k.cos_o - 1e-6;
      for (int c = 0; c < 3; ++c)
        for (const float* v : {t.v0, t.v1, t.v2})
          inside = inside && v[c] >= k.lo[c] && v[c] <= k.hi[c];
      unbounded += !inside;
      if (k.child < 0) {
        wrong += ~k.child != l.emitting[j];
        break;
      }
      ASSERT_LT(depth, KASHA_LIGHT_BVH_MAX_DEPTH);
      node = trail & 1 ? k.child : node + 1;
      trail >>= 1;
    }
  }
  EXPECT_EQ(wrong, 0) << "trails that end at another triangle";
  EXPECT_EQ(unbounded, 0) << "nodes that do not bound a triangle below them";
  EXPECT_EQ(bvh.nodes.size(), 2 * l.emitting.size() - 1);
}

TEST(LightBvh, TrailsLeadToTheirTriangles) {
  Lamps l;
  add_sphere(l, Vector3d(0, 0, 0), 1, 64, 1);  // 16 256 triangles
  add_grid(l, Vector3d(-3, 2, -3), Vector3d(6, 0, 0), Vector3d(0, 0, 6), 8, 5);
  const auto start = std::chrono::steady_clock::now();
  const LightBvh bvh = build_light_bvh(l.tris, l.emitting, l.power);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ bvh      ] %zu triangles: %zu nodes, depth %d, built in %.0f ms\n",
              l.emitting.size(), bvh.nodes.size(), bvh.depth, ms);
  expect_trails_lead_home(l, bvh);
  EXPECT_NEAR(bvh.nodes[0].phi, 1.0, 1e-6) << "the root's power is the whole";
}

TEST(LightBvh, CoincidentTrianglesStayWithinTheTrail) {
  // 70 000 copies of one triangle: no split separates them by position, and the tree still
  // reaches each within 64 levels (halving by count).
  Lamps l;
  for (int k = 0; k < 70000; ++k) l.add(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), 1);
  const LightBvh bvh = build_light_bvh(l.tris, l.emitting, l.power);
  std::printf("[ bvh      ] %zu coincident triangles: depth %d\n", l.emitting.size(), bvh.depth);
  EXPECT_LE(bvh.depth, 17);
  expect_trails_lead_home(l, bvh);
}

// ---------------------------------------------------------------------------------------------
// On the device.

const std::string kPickSource = std::string(kLightSampleKernelHead) + R"(
/* Work item j: the light BVH's probability of emitting triangle j at x, and light_pdf_from at its
 * centroid seen from x. */
__kernel void pick(KASHA_SCENE_PARAMS, __global const float* x_in, __global float* out) {
  KASHA_SCENE_VIEW(s);
  int j = get_global_id(0);
  float3 x = vload3(0, x_in);
  const __global KTriangle* t = &s.tris[s.light_tri[j]];
  float3 v0 = load_float3(t->v0), v1 = load_float3(t->v1), v2 = load_float3(t->v2);
  float3 y = (v0 + v1 + v2) / 3.0f, n = normalize(cross(v1 - v0, v2 - v0));
  out[2 * j] = light_triangle_share(&s) * light_bvh_pmf(s.light_nodes, s.light_trails[j], x);
  out[2 * j + 1] = light_pdf_from(&s, s.light_tri[j], x, y, dot(n, normalize(x - y)));
}

/* Work item i: sample_light_from at x: the emitting triangle it picked (its emitter), the density
 * it reports and light_pdf_from at the same point. */
__kernel void sample(KASHA_SCENE_PARAMS, __global const float* x_in, __global const float* u,
                     __global float* out) {
  SAMPLE_LIGHT_AT_X_IN();
  float3 to_x = x - p.position;
  out[3 * i] = (float)p.emitter;
  out[3 * i + 1] = pdf;
  out[3 * i + 2] = light_pdf_from(&s, s.light_tri[p.emitter], x, p.position,
                                  dot(p.normal, to_x) / length(to_x));
}
)";

// The sphere lamp of radius 1 at the origin (1 000 triangles) and a quad lamp above it facing
// down, twice as bright.
Lamps sphere_and_quad() {
  Lamps l;
  add_sphere(l, Vector3d(0, 0, 0), 1, 16, 1);
  add_grid(l, Vector3d(-1, -1, 3), Vector3d(0, 2, 0), Vector3d(2, 0, 0), 1, 2);
  return l;
}

TEST(KernelLightBvh, PicksSumToOneAndFollowPbrtsImportance) {
  const Lamps l = sphere_and_quad();
  const LightTables tables = light_tables(l.tris, l.emitting, l.power, int(l.tris.size()));
  TestKernel kernel(kPickSource, "light_bvh_pick_test.cl", "pick");
  kernel.buffer(1, tables.buffer);
  kernel.scalar(0, tables.params);
  kernel.input(2, std::vector<float>(1));
  for (const Vector3d& x : {Vector3d(2.5, 0.3, -0.4), Vector3d(0.2, 0.1, 1.5), Vector3d(0, 0, -6),
                            Vector3d(0.4, -0.3, 2.9)}) {
    kernel.input(3, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
    kernel.output(4, 2 * l.emitting.size());
    kernel.run(l.emitting.size());
    const std::vector<float> out = kernel.read(4);
    double sum = 0, worst = 0, zero = 0;
    for (size_t j = 0; j < l.emitting.size(); ++j) {
      const double want = reference_pick(tables.bvh, int(j), x), got = out[2 * j];
      sum += got;
      zero += want == 0;
      // Relative, but for picks near 0 (θ' near π/2, where the cosine's rounding is relative to 1).
      worst = std::max(worst, std::abs(got - want) / (want + 1e-4));
    }
    std::printf(
        "[ picks    ] x = (%g, %g, %g): sum %.7f, %.0f of %zu triangles at 0, largest error "
        "against the double reference %.2g\n",
        x.x(), x.y(), x.z(), sum, zero, l.emitting.size(), worst);
    EXPECT_NEAR(sum, 1.0, 1e-5);
    EXPECT_LT(worst, 1e-4);
    EXPECT_GT(zero, 0) << "some triangles face away from every x here";
  }
}

TEST(KernelLightBvh, SampledDensityIsLightPdfFrom) {
  constexpr size_t kSamples = 400000;
  const Lamps l = sphere_and_quad();
  const int n = static_cast<int>(l.emitting.size());
  const LightTables tables = light_tables(l.tris, l.emitting, l.power, n);
  TestKernel kernel(kPickSource, "light_bvh_sample_test.cl", "sample");
  kernel.buffer(1, tables.buffer);
  kernel.scalar(0, tables.params);
  kernel.input(2, std::vector<float>(1));
  const Vector3d x(1.6, 0.5, 0.8);  // near the sphere, below the quad
  kernel.input(3, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
  const std::vector<float> out = kernel.sample(4, uniforms(2 * kSamples, 23), 5, 3, kSamples);
  std::vector<double> chosen(n, 0.0), expected(n), by_power(n);
  double total_power = 0;
  for (double p : l.power) total_power += p;
  int mismatched = 0, zero = 0, away = 0;
  for (size_t i = 0; i < kSamples; ++i) {
    const int j = static_cast<int>(out[3 * i]);
    ASSERT_TRUE(j >= 0 && j < n);
    chosen[j] += 1;
    zero += !(out[3 * i + 1] > 0);
    mismatched += std::abs(out[3 * i + 2] - out[3 * i + 1]) > 1e-5 * out[3 * i + 1];
    // A triangle wholly facing away from x (every vertex behind its plane's front).
    const KTriangle& t = l.tris[l.emitting[j]];
    away += normal_of(t).dot(x - Vector3d(t.v0[0], t.v0[1], t.v0[2])) < 0;
  }
  double away_by_power = 0;
  for (int j = 0; j < n; ++j) {
    expected[j] = kSamples * reference_pick(tables.bvh, j, x);
    by_power[j] = kSamples * l.power[j] / total_power;
    const KTriangle& t = l.tris[l.emitting[j]];
    if (normal_of(t).dot(x - Vector3d(t.v0[0], t.v0[1], t.v0[2])) < 0) away_by_power += by_power[j];
  }
  std::printf(
      "[ sample   ] %zu samples: %d with a density other than light_pdf_from's, %d of density 0, "
      "%.1f %% on triangles facing away (%.1f %% by power)\n",
      kSamples, mismatched, zero, 100.0 * away / kSamples, 100.0 * away_by_power / kSamples);
  EXPECT_EQ(mismatched, 0);
  EXPECT_LE(zero, away) << "density 0 only from behind (area sampling of a far triangle)";
  // Where a node's bounds see x and none of its children's do, the choice goes by power: the
  // sphere's far side keeps some samples, fewer than by power alone.
  EXPECT_LT(away, 0.75 * away_by_power) << "triangles facing away get as many samples as by power";
  expect_fits("light BVH's choice", chosen, expected);
  expect_rejects("light BVH's choice against power alone", chosen, by_power);
}

TEST(KernelLightBvh, ClusterFacingAwayGetsNoSamples) {
  // A bright 16 × 16 grid lamp facing away from x (+z, x below it) and a dim quad lamp below x
  // facing it: by power the grid would take 90 % of the samples.
  constexpr size_t kSamples = 100000;
  Lamps l;
  add_grid(l, Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), 16, 9);
  const int grid = static_cast<int>(l.emitting.size());
  add_grid(l, Vector3d(0, 0, -4), Vector3d(1, 0, 0), Vector3d(0, 1, 0), 1, 1);
  const LightTables tables = light_tables(l.tris, l.emitting, l.power, int(l.tris.size()));
  TestKernel kernel(kPickSource, "light_bvh_away_test.cl", "sample");
  kernel.buffer(1, tables.buffer);
  kernel.scalar(0, tables.params);
  kernel.input(2, std::vector<float>(1));
  const Vector3d x(0.5, 0.5, -2);
  kernel.input(3, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
  const std::vector<float> out = kernel.sample(4, uniforms(2 * kSamples, 29), 5, 3, kSamples);
  size_t on_grid = 0;
  for (size_t i = 0; i < kSamples; ++i) on_grid += out[3 * i] < grid;
  double grid_power = 0, total = 0;
  for (size_t j = 0; j < l.power.size(); ++j)
    total += l.power[j], grid_power += j < size_t(grid) ? l.power[j] : 0;
  std::printf("[ away     ] %zu of %zu samples on the grid facing away (by power: %.0f %%)\n",
              on_grid, kSamples, 100 * grid_power / total);
  EXPECT_EQ(on_grid, 0u);
  EXPECT_GT(grid_power / total, 0.8);
}

}  // namespace
