// Device unit tests of next-event estimation from a shading point (kernels/lights/lights.h:
// sample_light_from, light_pdf_from, triangle_solid_angle, sample_spherical_triangle) and of the
// sample generator (kernels/sampling/sampler.h: Owen-scrambled Sobol pairs, and the independent
// PCG32 numbers of KASHA_SOBOL 0). χ² tests as in kernel_sampling_test.cpp: cells expected below 5
// pooled, a fit fails when p < 1e-4, and each test shows that its samples reject a plausible
// wrong density.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "chi2.h"
#include "kernel_harness.h"
#include "light_tables.h"
#include "shared/shared_types.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

// Solid angle of the triangle (a, b, c) seen from x, in double (Van Oosterom & Strackee 1983).
double solid_angle(const Vector3d& x, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d p = a - x, q = b - x, r = c - x;
  const double lp = p.norm(), lq = q.norm(), lr = r.norm();
  return 2 * std::atan2(std::abs(p.dot(q.cross(r))),
                        lp * lq * lr + p.dot(q) * lr + p.dot(r) * lq + q.dot(r) * lp);
}

Vector3d vertex(const float (&v)[3]) {
  return Vector3d(v[0], v[1], v[2]);
}

// ---------------------------------------------------------------------------------------------
// The solid angle of a triangle.

const char* const kSolidAngleSource = R"(
#include "lights/lights.h"
__kernel void solid_angle(__global const float* in, __global float* out) {
  size_t i = get_global_id(0);
  __global const float* v = in + 12 * i;
  out[i] = triangle_solid_angle((float3)(v[0], v[1], v[2]), (float3)(v[3], v[4], v[5]),
                                (float3)(v[6], v[7], v[8]), (float3)(v[9], v[10], v[11]));
}
)";

TEST(KernelLightSampler, SolidAngleMatchesDoublePrecision) {
  // Triangles of size 10^[-2, 0.5) at distance 10^[-1.5, 1.5) in random directions from random
  // points, so the solid angles span about 1e-7 .. 2π.
  constexpr size_t kCases = 20000;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(0, 1);
  std::vector<float> in;
  for (size_t i = 0; i < kCases; ++i) {
    const Vector3d x = Vector3d(unit(rng), unit(rng), unit(rng)) * 3;
    Vector3d dir(unit(rng), unit(rng), unit(rng));
    const double dist = std::pow(10, -1.5 + 3 * exponent(rng));
    const double size = std::pow(10, -2 + 2.5 * exponent(rng));
    const Vector3d centre = x + dist * dir.normalized();
    in.insert(in.end(), {float(x.x()), float(x.y()), float(x.z())});
    for (int k = 0; k < 3; ++k) {
      const Vector3d v = centre + size * Vector3d(unit(rng), unit(rng), unit(rng));
      in.insert(in.end(), {float(v.x()), float(v.y()), float(v.z())});
    }
  }
  TestKernel kernel(kSolidAngleSource, "solid_angle_test.cl", "solid_angle");
  const std::vector<float> out = kernel.sample(0, in, 1, 1, kCases);
  // The largest relative and absolute errors in ranges of the float inputs' exact solid angle,
  // and the cases that take the other side of KASHA_MIN_SPHERICAL_SOLID_ANGLE.
  const double edges[] = {0, 1e-5, 3e-4, 1e-2, 1, 7};
  double worst[5] = {0, 0, 0, 0, 0}, worst_abs[5] = {0, 0, 0, 0, 0}, flip_ratio = 1;
  int count[5] = {0, 0, 0, 0, 0}, flips = 0;
  for (size_t i = 0; i < kCases; ++i) {
    const float* v = &in[12 * i];
    const double want = solid_angle(Vector3d(v[0], v[1], v[2]), Vector3d(v[3], v[4], v[5]),
                                    Vector3d(v[6], v[7], v[8]), Vector3d(v[9], v[10], v[11]));
    const double err = std::abs(out[i] - want);
    for (int d = 0; d < 5; ++d)
      if (want >= edges[d] && want < edges[d + 1]) {
        worst[d] = std::max(worst[d], err / want), worst_abs[d] = std::max(worst_abs[d], err);
        ++count[d];
      }
    const double min_sa = KASHA_MIN_SPHERICAL_SOLID_ANGLE;
    if ((out[i] > KASHA_MIN_SPHERICAL_SOLID_ANGLE) != (want > min_sa)) {
      ++flips;
      flip_ratio = std::max({flip_ratio, want / min_sa, min_sa / want});
    }
  }
  for (int d = 0; d < 5; ++d)
    std::printf(
        "[ omega    ] solid angle in [%g, %g): %d cases, largest error %.2g relative, "
        "%.2g absolute\n",
        edges[d], edges[d + 1], count[d], worst[d], worst_abs[d]);
  std::printf(
      "[ omega    ] %d cases on the other side of %g than in double, all within a "
      "factor %.6f of it\n",
      flips, KASHA_MIN_SPHERICAL_SOLID_ANGLE, flip_ratio);
  EXPECT_LT(flip_ratio, 1.01);
  EXPECT_LT(worst_abs[0] + worst_abs[1], 1e-6);
  // Where the solid angle chooses spherical sampling and sets its pdf (above
  // 3e-4 sr), float agrees with double to 1e-3.
  EXPECT_LT(worst[2], 1e-3);
  EXPECT_LT(worst[3], 1e-4);
  EXPECT_LT(worst[4], 1e-4);
  for (int d = 2; d < 5; ++d) EXPECT_GT(count[d], 100) << "too few cases in range " << d;
}

// ---------------------------------------------------------------------------------------------
// Light points from a shading point: spherical or area sampling per triangle.

const char* const kLightFromSource = R"(
#include "lights/lights.h"
__kernel void light_from(KASHA_SCENE_PARAMS, __global const float* x_in, __global const float* u,
                         __global float* out) {
  KASHA_SCENE_VIEW(s);
  size_t i = get_global_id(0);
  float3 x = (float3)(x_in[0], x_in[1], x_in[2]);
  float pdf;
  /* u.x picks the light and, rescaled, the point with u.y (u[3 i + 1] is left unused). */
  LightPoint p = sample_light_from(&s, x, (float2)(u[3 * i], u[3 * i + 2]), &pdf);
  /* The triangle it picked: emitter e is emitting triangle light_count - 1 - e. */
  int k = s.light_count - 1 - p.emitter;
  float3 to_x = x - p.position;
  float cos_light = dot(p.normal, to_x) / length(to_x);
  __global float* o = out + 10 * i;
  vstore3(p.position, 0, o);
  vstore3(p.normal, 1, o);
  o[6] = (float)p.emitter;
  o[7] = pdf;
  o[8] = (float)k;
  o[9] = light_pdf_from(&s, s.light_tri[k], x, p.position, cos_light);
}
)";

// The solid angle from x of each barycentric cell of the triangle (v0, v1, v2) (the cells of
// triangle_cell), as shares of the triangle's.
std::vector<double> triangle_cell_solid_angle(const Vector3d& x, const Vector3d& v0,
                                              const Vector3d& v1, const Vector3d& v2, int k) {
  auto corner = [&](int i, int j) {
    return v0 + (double(i) / k) * (v1 - v0) + (double(j) / k) * (v2 - v0);
  };
  std::vector<double> share(k * k, 0.0);
  double sum = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      const Vector3d a = corner(i, j), b = corner(i + 1, j), c = corner(i, j + 1);
      double w = solid_angle(x, a, b, c);
      if (i + j < k - 1) w += solid_angle(x, b, corner(i + 1, j + 1), c);
      share[i * k + j] = w;
      sum += w;
    }
  const double whole = solid_angle(x, v0, v1, v2);
  EXPECT_NEAR(sum / whole, 1.0, 1e-9) << "cells' solid angles";
  for (double& s : share) s /= whole;
  return share;
}

struct TestLight {
  std::string name;
  Vector3d v0, v1, v2;
  double target;  // share of the power
  bool close;     // spherical and close, so area sampling differs strongly
};

TEST(KernelLightSampler, PointsFollowTheClaimedDensity) {
  constexpr size_t kSamples = 600000;
  constexpr int kGrid = 8;  // barycentric cells per triangle
  const Vector3d x(0.3, -0.2, 0.1);
  // Solid angles from x: 2.55 (large, close), 0.155 (grazing, cos_light ~0.2), 0.36 (seen from
  // behind), 1.3e-3 (small), 9e-5 and 1.8e-4 (the second seen from behind); the last three are
  // sampled by area (below KASHA_MIN_SPHERICAL_SOLID_ANGLE).
  std::vector<TestLight> lights = {
      {"large close", {-0.8, -1.0, 0.7}, {-0.9, 1.3, 0.7}, {1.6, -0.7, 0.7}, 0.3, true},
      {"grazing", {1.2, -0.6, -0.4}, {1.0, 0.5, 0.6}, {2.2, 0.3, -0.3}, 0.15, true},
      {"behind", {-0.6, -1.1, -0.5}, {0.4, -1.4, -0.2}, {-0.3, -1.2, 0.6}, 0.15, true},
      {"small", {-2.5, 1.5, -1.0}, {-2.5, 1.75, -1.0}, {-2.42, 1.5, -0.82}, 0.15, false},
      {"far", {4.0, 3.0, 2.0}, {4.0, 3.2, 1.96}, {4.2, 3.0, 2.1}, 0.15, false},
      {"far behind", {-3, -4, 3}, {-2.86, -4, 3.0}, {-3, -3.88, 3.04}, 0.1, false}};
  const int lights_n = static_cast<int>(lights.size());
  // Leaf triangles: the lights among non-emitting ones, emitter e = lights_n - 1 - j for light j.
  std::vector<KTriangle> tris;
  std::vector<int> light_tri;
  std::vector<double> power(lights_n), area(lights_n);
  for (int j = 0; j < lights_n; ++j) {
    TestLight& l = lights[j];
    const Vector3d away(9, 0, 0);
    tris.push_back(triangle(l.v0 + away, l.v1 + away, l.v2 + away, -1, 2 * j));
    light_tri.push_back(static_cast<int>(tris.size()));
    tris.push_back(triangle(l.v0, l.v1, l.v2, lights_n - 1 - j, 2 * j + 1));
    const KTriangle& t = tris.back();  // from here on the float vertices, as the device has them
    l.v0 = vertex(t.v0), l.v1 = vertex(t.v1), l.v2 = vertex(t.v2);
    area[j] = 0.5 * (l.v1 - l.v0).cross(l.v2 - l.v0).norm();
    power[j] = l.target;  // area · π · radiance: the emitter's radiance follows from it
  }
  const LightTables tables = light_tables(tris, light_tri, power, lights_n);
  TestKernel kernel(kLightFromSource, "light_from_test.cl", "light_from");
  kernel.buffer(1, tables.buffer);
  kernel.scalar(0, tables.params);
  kernel.input(2, std::vector<float>(1));  // scratch
  kernel.input(3, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
  const std::vector<float> out = kernel.sample(4, uniforms(3 * kSamples, 11), 5, 10, kSamples);

  // Per light: the selection probability of the light BVH at x, the solid angle, the
  // branch, the cells' shares of its points. The claimed density integrated over a cell: a
  // constant p / Ω in solid angle when spherical (so the share Ω(cell) / Ω), p / area in area
  // otherwise; the pdfs are checked against these below.
  const int cells = kGrid * kGrid;
  std::vector<double> p_light(lights_n), omega(lights_n);
  std::vector<bool> spherical(lights_n);
  std::vector<std::vector<double>> share(lights_n);
  std::vector<Eigen::Matrix<double, 2, 3>> to_bary(lights_n);
  std::vector<Vector3d> normal(lights_n);
  for (int j = 0; j < lights_n; ++j) {
    const TestLight& l = lights[j];
    p_light[j] = reference_pick(tables.bvh, j, x);  // the light BVH's choice at x
    omega[j] = solid_angle(x, l.v0, l.v1, l.v2);
    spherical[j] =
        omega[j] > KASHA_MIN_SPHERICAL_SOLID_ANGLE && omega[j] < KASHA_MAX_SPHERICAL_SOLID_ANGLE;
    share[j] = spherical[j] ? triangle_cell_solid_angle(x, l.v0, l.v1, l.v2, kGrid)
                            : triangle_cell_area(kGrid);
    Eigen::Matrix<double, 3, 2> e;
    e << l.v1 - l.v0, l.v2 - l.v0;
    to_bary[j] = (e.transpose() * e).inverse() * e.transpose();
    normal[j] = e.col(0).cross(e.col(1)).normalized();
    std::printf("[ light    ] %-11s solid angle %.3g, p %.3f, %s sampling, seen from %s\n",
                l.name.c_str(), omega[j], p_light[j], spherical[j] ? "spherical" : "area",
                normal[j].dot(x - l.v0) > 0 ? "the front" : "behind");
  }
  EXPECT_TRUE(spherical[0] && spherical[1] && spherical[2]);  // both branches are covered
  EXPECT_FALSE(spherical[3] || spherical[4] || spherical[5]);

  std::vector<std::vector<double>> observed(lights_n, std::vector<double>(cells + 1, 0.0));
  std::vector<double> chosen(lights_n, 0.0);
  std::vector<int> off_light(lights_n), bad_normal(lights_n), bad_pdf(lights_n),
      bad_pdf_from(lights_n), zero_pdf(lights_n);
  std::vector<double> max_plane(lights_n), max_outside(lights_n), max_pdf_err(lights_n),
      max_from_err(lights_n);
  for (size_t i = 0; i < kSamples; ++i) {
    const float* o = &out[10 * i];
    const int j = static_cast<int>(o[8]);
    ASSERT_TRUE(j >= 0 && j < lights_n);
    const TestLight& l = lights[j];
    chosen[j] += 1;
    const Vector3d p = at(out, 10 * i), r = p - l.v0;
    // On the light's plane, and its barycentrics (within rounding of the triangle: clamped in).
    // Spherical sampling lands slightly outside small triangles (float rounding in Arvo's
    // construction grows as the solid angle shrinks: 1.3e-4 at 3.7e-4 sr on PoCL, 1.1e-4 at 1.3e-3
    // sr on an NVIDIA H100), hence the threshold of 1e-2 sr.
    const double plane = std::abs(normal[j].dot(r)) / (1 + (p - x).norm());
    max_plane[j] = std::max(max_plane[j], plane);
    Eigen::Vector2d b = to_bary[j] * r;
    max_outside[j] = std::max({max_outside[j], -b[0], -b[1], b[0] + b[1] - 1});
    const double slack = 1e-4;
    if (plane > 1e-5 || b[0] < -slack || b[1] < -slack || b[0] + b[1] > 1 + slack) {
      ++off_light[j];
      observed[j][cells] += 1;
      continue;
    }
    b = b.cwiseMax(0.0);
    if (b.sum() > 1) b /= b.sum();
    observed[j][triangle_cell(b[0], b[1], kGrid)] += 1;
    if ((at(out, 10 * i + 3) - normal[j]).norm() > 1e-5 || o[6] != float(lights_n - 1 - j))
      ++bad_normal[j];
    // The solid-angle density the routine claims: p / Ω when spherical, p / area · d² / cos
    // (0 from behind) otherwise; and light_pdf_from at the point.
    const Vector3d to_x = x - p;
    const double d = to_x.norm(), cos_light = normal[j].dot(to_x) / d;
    double want = p_light[j] / omega[j];
    if (!spherical[j]) want = cos_light > 0 ? p_light[j] / area[j] * d * d / cos_light : 0.0;
    if (o[7] == 0) ++zero_pdf[j];
    const double pdf_err = want > 0 ? std::abs(o[7] - want) / want : std::abs(o[7]);
    const double from_err = std::abs(o[9] - o[7]) / std::max<double>(o[7], 1e-30);
    max_pdf_err[j] = std::max(max_pdf_err[j], pdf_err);
    max_from_err[j] = std::max(max_from_err[j], o[7] > 0 ? from_err : std::abs(o[9]));
    if (pdf_err > 1e-3) ++bad_pdf[j];
    if ((o[7] > 0 && from_err > 1e-3) || (o[7] == 0 && o[9] != 0)) ++bad_pdf_from[j];
  }

  std::vector<double> expected_choice(lights_n), wrong_choice(lights_n);
  double total_area = 0;
  for (double a : area) total_area += a;
  for (int j = 0; j < lights_n; ++j) {
    const TestLight& l = lights[j];
    std::printf(
        "[ light    ] %-11s %6.0f samples, %d off the triangle (farthest: %.2g from its plane, "
        "%.2g outside in barycentrics), pdf 0 in %d; pdf: largest relative error against the "
        "host's %.2g, against light_pdf_from %.2g\n",
        l.name.c_str(), chosen[j], off_light[j], max_plane[j], max_outside[j], zero_pdf[j],
        max_pdf_err[j], max_from_err[j]);
    EXPECT_EQ(off_light[j], 0) << l.name << ": points off the light triangle";
    EXPECT_EQ(bad_normal[j], 0) << l.name << ": normal or emitter";
    EXPECT_EQ(bad_pdf[j], 0) << l.name << ": pdf differs from the host's by over 1e-3";
    EXPECT_EQ(bad_pdf_from[j], 0) << l.name << ": pdf differs from light_pdf_from by over 1e-3";
    // Only area sampling of a triangle seen from behind fails (pdf 0); spherical sampling gives
    // points there a positive pdf, as light_pdf_from does.
    const bool behind = normal[j].dot(x - l.v0) < 0;
    EXPECT_EQ(zero_pdf[j], behind && !spherical[j] ? int(chosen[j]) : 0) << l.name;

    expected_choice[j] = kSamples * p_light[j];
    wrong_choice[j] = kSamples * area[j] / total_area;  // by area instead of power
    std::vector<double> expected(cells + 1, 0.0), wrong(cells + 1, 0.0);
    const std::vector<double> by_area = triangle_cell_area(kGrid);
    for (int c = 0; c < cells; ++c) {
      expected[c] = chosen[j] * share[j][c];
      wrong[c] = chosen[j] * by_area[c];  // uniform in area
    }
    if (chosen[j] == 0) continue;  // the BVH sees it facing away: the choice's fit checks it
    expect_fits("light point on " + l.name, observed[j], expected);
    if (l.close)
      expect_rejects("light point on " + l.name + ", uniform in area", observed[j], wrong);
  }
  expect_fits("light choice", chosen, expected_choice);
  expect_rejects("light choice by area", chosen, wrong_choice);
}

// ---------------------------------------------------------------------------------------------
// The sampler: Owen-scrambled Sobol pairs, or independent PCG32 numbers.

const char* const kSamplerSource = R"(
#include "sampling/sampler.h"
/* Work item i: sample first + i of `stream` (the independent sampler: pass `stream`, item i),
 * dimension pairs from .. from + pairs - 1. */
__kernel void draw(uint seed, uint stream, uint first, uint from, uint pairs, __global float* out) {
  uint i = get_global_id(0);
  Sampler s = sampler_start(seed, stream, first + i, stream, i);
  sampler_at(&s, from);
  __global float* o = out + 2 * pairs * i;
  for (uint k = 0; k < pairs; ++k) {
    float2 v = sample_2d(&s);
    o[2 * k] = v.x;
    o[2 * k + 1] = v.y;
  }
}

/* The same pairs 0 .. 3 of sample first + i three ways: drawn in order from a fresh sampler;
 * from a sampler started elsewhere, moved with sampler_next_sample and sampler_at, drawn in
 * reverse; and scrambled_sobol_2d with the seed sample_2d uses. */
__kernel void entry_points(uint seed, uint stream, uint first, __global float* out) {
  uint i = get_global_id(0), index = first + i;
  __global float* o = out + 24 * i;
  Sampler a = sampler_start(seed, stream, index, 0u, i);
  for (uint k = 0; k < 4; ++k) vstore2(sample_2d(&a), k, o);
  Sampler b = sampler_start(seed, stream, index + 12345u, 0u, i);
  sample_2d(&b);
  sample_2d(&b);
  sampler_next_sample(&b, index);
  for (int k = 3; k >= 0; --k) {
    sampler_at(&b, (uint)k);
    vstore2(sample_2d(&b), 4 + k, o);
  }
  uint key = hash_combine(hash_u32(seed), stream);
  for (uint k = 0; k < 4; ++k) vstore2(scrambled_sobol_2d(index, hash_combine(key, k)), 8 + k, o);
}

/* Photon i of pass `pass` (photons per pass `photons`): its first pair. */
__kernel void photon(uint seed, uint pass, int photons, __global float* out) {
  int i = get_global_id(0);
  Sampler s = photon_sampler(seed, pass, photons, i);
  vstore2(sample_2d(&s), i, out);
}

/* A plausible wrong sampler for two streams: one index shuffle for both (that of seed_a), only the
 * scramble of the coordinate per stream. Writes the first coordinate of each stream. */
__kernel void shared_shuffle(uint seed_a, uint seed_b, __global float* out) {
  uint i = get_global_id(0);
  uint index = reverse_bits_u32(nested_uniform_scramble(i, seed_a));
  out[2 * i] = (float)(nested_uniform_scramble(index, hash_combine(seed_a, 1u)) >> 8) * 0x1p-24f;
  out[2 * i + 1] = (float)(nested_uniform_scramble(index, hash_combine(seed_b, 1u)) >> 8) * 0x1p-24f;
}
)";

// `count` samples of `pairs` dimension pairs from pair `from`: 2 · pairs floats per sample.
std::vector<float> draw(TestKernel& kernel, std::uint32_t seed, std::uint32_t stream,
                        std::uint32_t first, std::uint32_t from, std::uint32_t pairs,
                        size_t count) {
  kernel.scalar(0, seed);
  kernel.scalar(1, stream);
  kernel.scalar(2, first);
  kernel.scalar(3, from);
  kernel.scalar(4, pairs);
  kernel.output(5, 2 * pairs * count);
  kernel.run(count);
  return kernel.read(5);
}

// Every `stride`-th value of v from `offset`.
std::vector<float> column(const std::vector<float>& v, size_t offset, size_t stride) {
  std::vector<float> c;
  for (size_t i = offset; i < v.size(); i += stride) c.push_back(v[i]);
  return c;
}

// Counts of the points (a[i], b[i]) in an n × n grid over [0, 1)² (cell ia · n + ib).
std::vector<double> grid_counts(const std::vector<float>& a, const std::vector<float>& b, int n) {
  std::vector<double> counts(n * n, 0.0);
  for (size_t i = 0; i < a.size(); ++i)
    counts[cell_of(a[i], 0, 1, n) * n + cell_of(b[i], 0, 1, n)] += 1;
  return counts;
}

// Expected counts of `count` numbers in n equal cells of [0, 1) under the density
// 1 + tilt · (2u - 1) (the uniform one for tilt 0): a plausible bias for the wrong density.
std::vector<double> cells_expected(size_t count, int n, double tilt) {
  std::vector<double> e(n);
  for (int c = 0; c < n; ++c) e[c] = double(count) / n * (1 + tilt * (2 * (c + 0.5) / n - 1));
  return e;
}

// The same for points in the n × n grid of grid_counts, tilted along a.
std::vector<double> grid_expected(size_t count, int n, double tilt) {
  const std::vector<double> row = cells_expected(count, n, tilt);
  std::vector<double> e(n * n);
  for (int c = 0; c < n * n; ++c) e[c] = row[c / n] / n;
  return e;
}

// A uniform sample set (points (a, b)) on an n × n grid: fits the uniform density, rejects one
// tilted by 10%.
void expect_uniform(const std::string& what, const std::vector<float>& a,
                    const std::vector<float>& b, int n) {
  const std::vector<double> counts = grid_counts(a, b, n);
  expect_fits(what, counts, grid_expected(a.size(), n, 0));
  expect_rejects(what + ", tilted 10%", counts, grid_expected(a.size(), n, 0.1));
}

// The number of elementary intervals of area 2^-m (all shapes 2^-s × 2^-(m - s)) that do not hold
// exactly one of the 2^m points (x[first + i], y[first + i]).
int net_defects(const std::vector<float>& x, const std::vector<float>& y, size_t first, int m) {
  const size_t count = size_t(1) << m;
  int defects = 0;
  std::vector<int> counts(count);
  for (int s = 0; s <= m; ++s) {
    std::fill(counts.begin(), counts.end(), 0);
    for (size_t i = first; i < first + count; ++i) {
      // Coordinates are multiples of 2^-24: the cells come exactly from the top bits.
      const auto xi = static_cast<std::uint32_t>(x[i] * 0x1p24f);
      const auto yi = static_cast<std::uint32_t>(y[i] * 0x1p24f);
      ++counts[((xi >> (24 - s)) << (m - s)) | (yi >> (24 - (m - s)))];
    }
    for (int c : counts) defects += c != 1;
  }
  return defects;
}

TEST(KernelSampler, SobolPairsAreNets) {
  constexpr size_t kPoints = 4096;
  constexpr std::uint32_t kPairs = 4;
  TestKernel kernel(kSamplerSource, "sampler_test.cl", "draw");
  int nets = 0, defects = 0, straddling = 0, straddling_defects = 0;
  for (std::uint32_t seed : {1u, 2u, 0x9e3779b9u, 4242u})
    for (std::uint32_t stream : {0u, 12345u, 1u << 20}) {
      const std::vector<float> v = draw(kernel, seed, stream, 0, 0, kPairs, kPoints);
      for (std::uint32_t pair = 0; pair < kPairs; ++pair) {
        const std::vector<float> x = column(v, 2 * pair, 2 * kPairs),
                                 y = column(v, 2 * pair + 1, 2 * kPairs);
        for (int m = 4; m <= 10; ++m) {
          const size_t block = size_t(1) << m;
          // Every aligned block: the first 2^m points, the next 2^m (pass 2 continuing pass 1),
          // and so on.
          for (size_t first = 0; first + block <= kPoints; first += block, ++nets) {
            const int d = net_defects(x, y, first, m);
            defects += d;
            EXPECT_EQ(d, 0) << "seed " << seed << ", stream " << stream << ", pair " << pair
                            << ": points " << first << " .. " << first + block - 1 << " are no (0, "
                            << m << ", 2)-net";
          }
          // A block straddling two aligned ones need not be a net: the check can fail.
          straddling_defects += net_defects(x, y, block / 2, m) > 0;
          ++straddling;
        }
      }
    }
  std::printf("[ nets     ] %d aligned blocks of 2^4 .. 2^10 points: %d defective intervals\n",
              nets, defects);
  std::printf("[ nets     ] %d blocks straddling two aligned ones: %d are not nets\n", straddling,
              straddling_defects);
  EXPECT_GT(straddling_defects, straddling / 2) << "the net check cannot fail";
}

TEST(KernelSampler, SobolIsUniform) {
  constexpr size_t kPoints = 150000;  // not a power of 2
  constexpr std::uint32_t kPairs = 4;
  constexpr int kGrid = 16;
  TestKernel kernel(kSamplerSource, "sampler_test.cl", "draw");
  for (std::uint32_t stream : {0u, 77u}) {
    // From sample 1000 on: the middle of a pixel's samples over passes.
    const std::vector<float> v = draw(kernel, 9, stream, 1000, 0, kPairs, kPoints);
    for (std::uint32_t pair = 0; pair < kPairs; pair += 3)
      expect_uniform("sobol stream " + std::to_string(stream) + " pair " + std::to_string(pair),
                     column(v, 2 * pair, 2 * kPairs), column(v, 2 * pair + 1, 2 * kPairs), kGrid);
  }
}

TEST(KernelSampler, SobolPairsAndStreamsAreUncorrelated) {
  constexpr size_t kPoints = 150000;
  constexpr std::uint32_t kPairs = 4;
  constexpr int kGrid = 16;
  TestKernel kernel(kSamplerSource, "sampler_test.cl", "draw");
  const std::vector<float> a = draw(kernel, 3, 5, 0, 0, kPairs, kPoints);
  const std::vector<float> b = draw(kernel, 3, 6, 0, 0, kPairs, kPoints);
  const std::vector<double> uniform = grid_expected(kPoints, kGrid, 0);
  // Dimension pairs of one stream against each other, at the same indices.
  expect_fits("sobol pair 0 x vs pair 1 x", grid_counts(column(a, 0, 8), column(a, 2, 8), kGrid),
              uniform);
  expect_fits("sobol pair 0 y vs pair 1 y", grid_counts(column(a, 1, 8), column(a, 3, 8), kGrid),
              uniform);
  expect_fits("sobol pair 0 x vs pair 3 y", grid_counts(column(a, 0, 8), column(a, 7, 8), kGrid),
              uniform);
  // Two streams (neighbouring pixels) at the same index.
  expect_fits("sobol stream 5 vs stream 6, pair 0 x",
              grid_counts(column(a, 0, 8), column(b, 0, 8), kGrid), uniform);
  expect_fits("sobol stream 5 vs stream 6, pair 2 y",
              grid_counts(column(a, 5, 8), column(b, 5, 8), kGrid), uniform);
  // Streams that share the index shuffle and differ only in the scramble of the coordinates are
  // correlated: the same test rejects them.
  TestKernel shared(kSamplerSource, "sampler_test.cl", "shared_shuffle");
  shared.scalar(0, 0x1234u);
  shared.scalar(1, 0x5678u);
  shared.output(2, 2 * kPoints);
  shared.run(kPoints);
  const std::vector<float> s = shared.read(2);
  expect_rejects("streams sharing the index shuffle",
                 grid_counts(column(s, 0, 2), column(s, 1, 2), kGrid), uniform);
}

TEST(KernelSampler, SobolIsDeterministic) {
  constexpr size_t kPoints = 4096;
  TestKernel kernel(kSamplerSource, "sampler_test.cl", "draw");
  const std::vector<float> first = draw(kernel, 17, 3, 100, 0, 8, kPoints);
  const std::vector<float> again = draw(kernel, 17, 3, 100, 0, 8, kPoints);
  EXPECT_EQ(std::memcmp(first.data(), again.data(), first.size() * sizeof(float)), 0)
      << "two runs differ";
  // Pair 5 onwards, drawn from sampler_at(5): the same as pairs 5 .. 7 drawn in order.
  const std::vector<float> later = draw(kernel, 17, 3, 100, 5, 3, kPoints);
  size_t at_differs = 0;
  for (size_t i = 0; i < kPoints; ++i)
    at_differs += std::memcmp(&later[6 * i], &first[16 * i + 10], 6 * sizeof(float)) != 0;
  EXPECT_EQ(at_differs, 0u) << "sampler_at";
  // The comparisons can fail: another seed, stream or index gives other numbers.
  size_t same = 0;
  for (const auto& other :
       {draw(kernel, 18, 3, 100, 0, 8, kPoints), draw(kernel, 17, 4, 100, 0, 8, kPoints),
        draw(kernel, 17, 3, 101, 0, 8, kPoints)})
    for (size_t i = 0; i < first.size(); ++i) same += other[i] == first[i];
  EXPECT_LT(same, first.size() / 100) << "numbers do not depend on seed, stream and index";

  TestKernel entry(kSamplerSource, "sampler_test.cl", "entry_points");
  entry.scalar(0, 17u);
  entry.scalar(1, 3u);
  entry.scalar(2, 100u);
  entry.output(3, 24 * kPoints);
  entry.run(kPoints);
  const std::vector<float> e = entry.read(3);
  size_t moved_differs = 0, direct_differs = 0, draw_differs = 0;
  for (size_t i = 0; i < kPoints; ++i) {
    const float* o = &e[24 * i];
    moved_differs += std::memcmp(o, o + 8, 8 * sizeof(float)) != 0;
    direct_differs += std::memcmp(o, o + 16, 8 * sizeof(float)) != 0;
    draw_differs += std::memcmp(o, &first[16 * i], 8 * sizeof(float)) != 0;
  }
  EXPECT_EQ(moved_differs, 0u) << "sampler_next_sample and sampler_at";
  EXPECT_EQ(direct_differs, 0u) << "scrambled_sobol_2d with the sampler's seed";
  EXPECT_EQ(draw_differs, 0u) << "another kernel";
  std::printf(
      "[ sobol    ] %zu samples x 8 pairs bit-identical over two runs, sampler_at, "
      "sampler_next_sample and scrambled_sobol_2d; other seed/stream/index: %zu equal\n",
      kPoints, same);
}

// Independent numbers (KASHA_SOBOL 0) for `items` work items of pass 2, seed 21: 4 pairs each.
std::vector<float> independent_numbers(size_t items) {
  KernelDefines defines = test_kernel_defines();
  defines["KASHA_SOBOL"] = "0";
  TestKernel kernel(kSamplerSource, "sampler_independent_test.cl", "draw", defines);
  std::vector<float> v = draw(kernel, 21, 2, 0, 0, 4, items);
  const std::vector<float> again = draw(kernel, 21, 2, 0, 0, 4, items);
  EXPECT_EQ(std::memcmp(v.data(), again.data(), v.size() * sizeof(float)), 0) << "two runs differ";
  return v;
}

TEST(KernelSampler, IndependentSamplerIsUniform) {
  const std::vector<float> v = independent_numbers(100000);
  // All numbers, one dimension: 64 cells.
  std::vector<double> counts(64, 0.0);
  for (float u : v) counts[cell_of(u, 0, 1, 64)] += 1;
  expect_fits("independent numbers", counts, cells_expected(v.size(), 64, 0));
  expect_rejects("independent numbers, tilted 10%", counts, cells_expected(v.size(), 64, 0.1));
  // Within a pair, and consecutive pairs of a work item.
  expect_uniform("independent pair 0", column(v, 0, 8), column(v, 1, 8), 16);
  expect_uniform("independent pair 1 y vs pair 2 x", column(v, 3, 8), column(v, 4, 8), 16);
}

// Neighbouring work items (pixels, photons) draw unrelated numbers. Before rng_seed hashed
// (seed, pass, item), items i and i + 1 got PCG32 states a constant apart and increments one bit
// apart: chi2 = 836, df = 255 (p = 7e-63) for the first numbers of items 2k and 2k + 1.
TEST(KernelSampler, IndependentSamplerItemsAreUncorrelated) {
  const std::vector<float> v = independent_numbers(100000);
  expect_uniform("independent items 2k vs 2k + 1, first number", column(v, 0, 16), column(v, 8, 16),
                 16);
  expect_uniform("independent items 2k vs 2k + 1, second number", column(v, 1, 16),
                 column(v, 9, 16), 16);
}

}  // namespace

TEST(KernelSampler, PhotonSequencesDoNotRepeatAfter2To32Photons) {
  // 2^18 photons per pass: pass 16384 starts at photon number 2^32, which a 32-bit index would
  // have wrapped to pass 0's numbers. It is the start of a stream of its own instead.
  const int photons = 1 << 18, n = 4096;
  TestKernel kernel(kSamplerSource, "sampler_test.cl", "photon");
  auto first_pairs = [&](unsigned pass) {
    kernel.scalar(0, 7u);
    kernel.scalar(1, pass);
    kernel.scalar(2, photons);
    kernel.output(3, 2 * n);
    kernel.run(n);
    return kernel.read(3);
  };
  const std::vector<float> pass0 = first_pairs(0), pass16384 = first_pairs(16384),
                           pass1 = first_pairs(1);
  int same_wrap = 0, same_next = 0;
  for (int i = 0; i < 2 * n; ++i)
    same_wrap += pass0[i] == pass16384[i], same_next += pass0[i] == pass1[i];
  EXPECT_LT(same_wrap, 10) << "pass 16384 repeats pass 0";
  EXPECT_LT(same_next, 10);
}
