// χ² goodness-of-fit tests of the kernels' sampling routines against their densities: uniforms
// drawn on the host with fixed seeds go through the device routine, and the samples are binned on
// the host into cells whose expected counts integrate the density exactly. Cells expected below 5
// are pooled; a test fails when p < 1e-4. Each test also checks that the same samples reject a
// plausible wrong density (p < 1e-4), so the test is known to be able to fail.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "chi2.h"
#include "kernel_harness.h"
#include "render/device_scene.h"

using namespace kasha;
using Eigen::Vector3d;
using namespace kasha::test;

namespace {

// The azimuth of d about n in [0, 2π) in the frame (s, t).
double azimuth(const Vector3d& d, const Vector3d& s, const Vector3d& t) {
  double phi = std::atan2(d.dot(t), d.dot(s));
  return phi < 0 ? phi + 2 * M_PI : phi;
}

// ---------------------------------------------------------------------------------------------
// Cosine-weighted hemisphere.

const char* const kCosineSource = R"(
#include "sampling/sampling.h"
__kernel void cosine(__global const float* n_in, __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float3 n = (float3)(n_in[0], n_in[1], n_in[2]);
  float3 d = sample_cosine_hemisphere(n, u[2 * i], u[2 * i + 1]);
  out[4 * i] = d.x;
  out[4 * i + 1] = d.y;
  out[4 * i + 2] = d.z;
  out[4 * i + 3] = cosine_hemisphere_pdf(dot(d, n));
}
)";

TEST(KernelSampling, CosineHemisphereFitsItsDensity) {
  constexpr size_t kSamples = 200000;  // per normal
  constexpr int kCos = 10, kPhi = 16;  // cells in cos θ and φ about the normal
  TestKernel kernel(kCosineSource, "cosine_test.cl", "cosine");
  const std::vector<std::pair<std::string, Vector3d>> normals = {
      {"+z", Vector3d(0, 0, 1)},
      {"-z", Vector3d(0, 0, -1)},
      {"oblique", Vector3d(0.48, -0.6, 0.64)},
      {"near -z", Vector3d(1e-3, 2e-3, -1).normalized()}};
  std::uint32_t seed = 1;
  for (const auto& [name, normal] : normals) {
    std::vector<float> n = {float(normal.x()), float(normal.y()), float(normal.z())};
    const Vector3d nf(n[0], n[1], n[2]);  // the normal as the device has it
    kernel.input(0, n);
    std::vector<float> out = kernel.sample(1, uniforms(2 * kSamples, seed++), 2, 4, kSamples);
    Vector3d s, t;
    frame(nf.normalized(), s, t);
    std::vector<double> observed(kCos * kPhi, 0.0), expected(kCos * kPhi), uniform(kCos * kPhi);
    size_t bad = 0, bad_pdf = 0;
    for (size_t i = 0; i < kSamples; ++i) {
      Vector3d d = at(out, 4 * i);
      double c = d.dot(nf);
      if (std::abs(d.norm() - 1) > 1e-5 || !(c > 0)) ++bad;
      if (std::abs(out[4 * i + 3] - std::max(c, 0.0) / M_PI) > 1e-6) ++bad_pdf;
      observed[cell_of(c, 0, 1, kCos) * kPhi + cell_of(azimuth(d, s, t), 0, 2 * M_PI, kPhi)] += 1;
    }
    EXPECT_EQ(bad, 0u) << name << ": samples off the unit upper hemisphere";
    EXPECT_EQ(bad_pdf, 0u) << name << ": cosine_hemisphere_pdf is not cos θ / π";
    for (int a = 0; a < kCos; ++a) {
      double c0 = double(a) / kCos, c1 = double(a + 1) / kCos;
      for (int b = 0; b < kPhi; ++b) {
        // ∫ cos θ / π dω over the cell = (c1² - c0²) / 2 · Δφ / π.
        expected[a * kPhi + b] = kSamples * (c1 * c1 - c0 * c0) / 2 * (2.0 / kPhi);
        uniform[a * kPhi + b] = kSamples * (c1 - c0) / kPhi;  // 1 / 2π: a uniform hemisphere
      }
    }
    expect_fits("cosine hemisphere about " + name, observed, expected);
    expect_rejects("cosine hemisphere about " + name, observed, uniform);
  }
}

// ---------------------------------------------------------------------------------------------
// The Henyey–Greenstein phase function (media/phase.h).

const char* const kPhaseSource = R"(
#include "media/phase.h"
__kernel void phase(__global const float* in, __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float3 wo = (float3)(in[0], in[1], in[2]);
  float pdf;
  float3 d = hg_sample(wo, in[3], (float2)(u[2 * i], u[2 * i + 1]), &pdf);
  out[4 * i] = d.x;
  out[4 * i + 1] = d.y;
  out[4 * i + 2] = d.z;
  out[4 * i + 3] = pdf;
}
)";

// The share of Henyey–Greenstein's directions with cos θ (to wo) below c: its marginal's integral.
double hg_cdf(double c, double g) {
  if (std::abs(g) < 1e-3) return (c + 1) / 2;
  return (1 - g * g) / (2 * g) * (1 / std::abs(1 - g) - 1 / std::sqrt(1 + g * g + 2 * g * c));
}

TEST(KernelSampling, HenyeyGreensteinFitsItsDensity) {
  constexpr size_t kSamples = 200000;
  constexpr int kCos = 20, kPhi = 8;
  TestKernel kernel(kPhaseSource, "phase_test.cl", "phase");
  const Vector3d wo = Vector3d(0.3, -0.5, 0.81).normalized();
  std::uint32_t seed = 11;
  for (double g : {0.0, 0.7, -0.4, 0.95}) {
    kernel.input(0, std::vector<float>{float(wo.x()), float(wo.y()), float(wo.z()), float(g)});
    std::vector<float> out = kernel.sample(1, uniforms(2 * kSamples, seed++), 2, 4, kSamples);
    const Vector3d w(float(wo.x()), float(wo.y()), float(wo.z()));
    Vector3d s, t;
    frame(w.normalized(), s, t);
    std::vector<double> observed(kCos * kPhi, 0.0), expected(kCos * kPhi), uniform(kCos * kPhi);
    size_t bad = 0, bad_pdf = 0;
    for (size_t i = 0; i < kSamples; ++i) {
      const Vector3d d = at(out, 4 * i);
      const double c = std::clamp(d.dot(w.normalized()), -1.0, 1.0);
      if (std::abs(d.norm() - 1) > 1e-5) ++bad;
      const double hg = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g + 2 * g * c, 1.5));
      if (std::abs(out[4 * i + 3] - hg) > 1e-3 * hg + 1e-6) ++bad_pdf;
      observed[cell_of(c, -1, 1, kCos) * kPhi + cell_of(azimuth(d, s, t), 0, 2 * M_PI, kPhi)] += 1;
    }
    const std::string name = "g " + std::to_string(g);
    EXPECT_EQ(bad, 0u) << name << ": directions off the unit sphere";
    EXPECT_EQ(bad_pdf, 0u) << name << ": the density returned is not the phase function's";
    for (int a = 0; a < kCos; ++a) {
      const double c0 = -1 + 2.0 * a / kCos, c1 = -1 + 2.0 * (a + 1) / kCos;
      for (int b = 0; b < kPhi; ++b) {
        expected[a * kPhi + b] = kSamples * (hg_cdf(c1, g) - hg_cdf(c0, g)) / kPhi;
        // The other sign of g: the mirror image (forward for backward scattering).
        uniform[a * kPhi + b] = kSamples * (hg_cdf(c1, g == 0 ? 0.3 : -g) - hg_cdf(c0, g == 0 ? 0.3 : -g)) / kPhi;
      }
    }
    expect_fits("Henyey-Greenstein " + name, observed, expected);
    expect_rejects("Henyey-Greenstein " + name, observed, uniform);
  }
}

// ---------------------------------------------------------------------------------------------
// The free flight's distance over a spectrum (transport/medium_flight.h, photon_medium.h): a bin
// drawn by its share of the power, then bin j's exponential; the distances follow the mixture
// p(t) = Σ_j c_j σt_j e^{−σt_j t}.

const char* const kFlightSource = R"(
#include "transport/photon_medium.h"
__kernel void flight_distance(__global const float* power, __global const float* sigma, __global const float* u,
                              __global float* out) {
  size_t i = get_global_id(0);
  Photon p;
  for (int k = 0; k < KASHA_BINS; ++k) p.power[k] = power[k];
  int j = photon_bin_by_power(&p, u[2 * i], photon_total(&p));
  out[i] = flight_depth(u[2 * i + 1]) / sigma[j];
}
)";

TEST(KernelSampling, FreeFlightDistancesFollowTheMixtureOverBins) {
  constexpr size_t kSamples = 200000;
  constexpr int kCells = 40;
  KernelDefines defines = test_kernel_defines();
  defines["KASHA_MEDIA"] = "1";
  defines["KASHA_SCATTERING"] = "1";
  defines["KASHA_MEDIA_COUNT"] = "1";
  TestKernel kernel(kFlightSource, "flight_test.cl", "flight_distance", defines);
  // Four bins; the third carries nothing and must never be drawn (its σt would show).
  const std::vector<float> power = {1, 3, 0, 2}, sigma = {0.5f, 2, 40, 4};
  kernel.input(0, power);
  kernel.input(1, sigma);
  const std::vector<float> t = kernel.sample(2, uniforms(2 * kSamples, 23), 3, 1, kSamples);
  const double total = 6;
  auto cdf = [&](double x, const std::vector<float>& s) {
    double f = 0;
    for (size_t j = 0; j < power.size(); ++j) f += power[j] / total * (1 - std::exp(-s[j] * x));
    return f;
  };
  // Cells of equal width up to 8 mean free paths of the thinnest bin, and one beyond.
  const double top = 8 / 0.5;
  std::vector<double> observed(kCells + 1, 0.0), expected(kCells + 1), grey(kCells + 1);
  for (float x : t) observed[x >= top ? kCells : cell_of(x, 0, top, kCells)] += 1;
  // A grey flight, one σt for every bin (their power-weighted mean), must be rejected.
  const float mean = (1 * 0.5f + 3 * 2 + 2 * 4) / 6.0f;
  const std::vector<float> flat(4, mean);
  for (int c = 0; c <= kCells; ++c) {
    const double a = top * c / kCells, b = c == kCells ? INFINITY : top * (c + 1) / kCells;
    expected[c] = kSamples * ((c == kCells ? 1.0 : cdf(b, sigma)) - cdf(a, sigma));
    grey[c] = kSamples * ((c == kCells ? 1.0 : cdf(b, flat)) - cdf(a, flat));
  }
  expect_fits("free flight over bins", observed, expected);
  expect_rejects("free flight over bins", observed, grey);
}

// ---------------------------------------------------------------------------------------------
// The tabulated gloss lobe.

const char* const kLobeSource = R"(
#include "materials/gloss_lobe.h"
__kernel void lobe(__global const KMaterial* m, __global const float* lobes,
                   __global const float* mirror_in, __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float3 mirror = (float3)(mirror_in[0], mirror_in[1], mirror_in[2]);
  float pdf;
  float3 d = sample_lobe(m, lobes, mirror, u[3 * i], u[3 * i + 1], u[3 * i + 2], &pdf);
  out[5 * i] = d.x;
  out[5 * i + 1] = d.y;
  out[5 * i + 2] = d.z;
  out[5 * i + 3] = pdf;
  out[5 * i + 4] = lobe_pdf(m, lobes, dot(d, mirror));
}
)";

GlossDesc lobe_gloss(std::vector<double> profile_value) {
  GlossDesc g;
  g.reflectance = 0.5;
  g.cone_deg = 12;
  g.profile_deg = {0, 4, 8, 12};
  g.profile_value = std::move(profile_value);
  return g;
}

TEST(KernelSampling, GlossLobeFitsItsTable) {
  constexpr size_t kSamples = 500000;  // per mirror direction
  // Cells: each of the table's rings split in 4 equal steps of cos δ (within a ring the sampler is
  // uniform in cos δ, not in δ), times 4 in φ.
  constexpr int K = KASHA_LOBE_CELLS, kSub = 4, kPhi = 4;
  const GlossDesc gloss = lobe_gloss({1, 0.7, 0.25, 0});
  const std::vector<float> table = gloss_lobe_table(gloss);
  // Another table first, so the material's offset matters: a uniform 12° cone.
  GlossDesc uniform_cone = gloss;
  uniform_cone.profile_deg.clear(), uniform_cone.profile_value.clear();
  std::vector<float> lobes = gloss_lobe_table(uniform_cone);
  KMaterial m{};
  m.lobe = static_cast<int>(lobes.size());
  m.gloss = static_cast<float>(gloss.reflectance);
  m.cone_rad = static_cast<float>(gloss.cone_deg * M_PI / 180);
  lobes.insert(lobes.end(), table.begin(), table.end());

  TestKernel kernel(kLobeSource, "lobe_test.cl", "lobe");
  kernel.input(0, std::vector<KMaterial>{m});
  kernel.input(1, lobes);
  const double width = double(m.cone_rad) / K;
  // Expected counts per cell from ring densities: p_k ∫ dω over (sub-ring, φ cell).
  auto expected_from = [&](const std::vector<float>& tab) {
    std::vector<double> e(K * kSub * kPhi + 1, 0.0);  // the last cell: outside the cone
    double total = 0;
    for (int k = 0; k < K; ++k)
      for (int h = 0; h < kSub; ++h) {
        double c0 = std::cos(k * width), c1 = std::cos((k + 1) * width);
        double lo = c0 + (c1 - c0) * h / kSub, hi = c0 + (c1 - c0) * (h + 1) / kSub;
        double mass = tab[k] * 2 * M_PI * (lo - hi);
        total += mass;
        for (int b = 0; b < kPhi; ++b) e[(k * kSub + h) * kPhi + b] = kSamples * mass / kPhi;
      }
    EXPECT_NEAR(total, 1.0, 1e-5) << "ring masses of the table";
    return e;
  };
  const std::vector<double> expected = expected_from(table);
  const std::vector<double> wrong = expected_from(gloss_lobe_table(lobe_gloss({1, 0.6, 0.25, 0})));

  std::uint32_t seed = 100;
  for (const auto& [name, mirror] : {std::pair<std::string, Vector3d>{"+z", Vector3d(0, 0, 1)},
                                     {"oblique", Vector3d(-0.36, 0.48, 0.8)}}) {
    std::vector<float> mf = {float(mirror.x()), float(mirror.y()), float(mirror.z())};
    const Vector3d md(mf[0], mf[1], mf[2]);
    kernel.input(2, mf);
    std::vector<float> out = kernel.sample(3, uniforms(3 * kSamples, seed++), 4, 5, kSamples);
    Vector3d s, t;
    frame(md.normalized(), s, t);
    std::vector<double> observed(expected.size(), 0.0);
    size_t bad_pdf = 0, boundary = 0, off_unit = 0;
    for (size_t i = 0; i < kSamples; ++i) {
      Vector3d d = at(out, 5 * i);
      if (std::abs(d.norm() - 1) > 1e-5) ++off_unit;
      double delta = std::atan2(d.cross(md).norm(), d.dot(md));
      // Float rounding moves δ by a few 2⁻²⁴ / sin δ (by at most 2 in these samples).
      double slack = 8 * 0x1p-24 / std::max(std::sin(delta), 1e-3);
      int k = static_cast<int>(delta / width);
      if (k >= K && delta < K * width + slack) k = K - 1;
      if (k >= K) {
        observed.back() += 1;
        continue;
      }
      double c0 = std::cos(k * width), c1 = std::cos((k + 1) * width), c = std::cos(delta);
      int h = std::clamp(static_cast<int>((c0 - c) / (c0 - c1) * kSub), 0, kSub - 1);
      observed[(k * kSub + h) * kPhi + cell_of(azimuth(d, s, t), 0, 2 * M_PI, kPhi)] += 1;
      // The returned pdf and lobe_pdf of the direction are both the table's density of the ring
      // the direction lies in; within rounding of a ring edge, that of the ring across it.
      const float pdf = out[5 * i + 3], evaluated = out[5 * i + 4];
      double frac = delta / width - k;
      bool near_lower = k > 0 && frac * width < slack, near_upper = (1 - frac) * width < slack;
      if (near_lower || near_upper) ++boundary;
      auto ok = [&](float p) {
        return p == table[k] || (near_lower && p == table[k - 1]) ||
               (near_upper && p == (k + 1 < K ? table[k + 1] : 0.0f));
      };
      if (!ok(pdf) || !ok(evaluated)) ++bad_pdf;
    }
    EXPECT_EQ(off_unit, 0u) << name << ": directions not of unit length";
    EXPECT_EQ(bad_pdf, 0u) << name << ": pdf differs from lobe_pdf or the table";
    EXPECT_LT(boundary, kSamples / 100) << name << ": samples within rounding of a ring edge";
    expect_fits("gloss lobe about " + name, observed, expected);
    expect_rejects("gloss lobe about " + name, observed, wrong);
  }
}

// ---------------------------------------------------------------------------------------------
// Uniform points on a triangle.

const char* const kTriangleSource = R"(
#include "sampling/sampling.h"
__kernel void triangle(__global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float2 b = sample_triangle(u[2 * i], u[2 * i + 1]);
  out[2 * i] = b.x;
  out[2 * i + 1] = b.y;
}
)";

// s ln s, 0 at 0.
double s_log_s(double s) {
  return s > 0 ? s * std::log(s) : 0.0;
}

// The density 1/(b1 + b2) (the warp without its square root) integrated over each triangle cell.
std::vector<double> triangle_cell_without_sqrt(int k) {
  std::vector<double> share(k * k, 0.0);
  const double w = 1.0 / k;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      double x0 = i * w, y0 = j * w, s0 = x0 + y0;
      if (i + j < k - 1)  // ∬ dx dy / (x + y) over the square: second difference of s ln s
        share[i * k + j] = s_log_s(s0 + 2 * w) - 2 * s_log_s(s0 + w) + s_log_s(s0);
      else  // the half below x + y = s0 + w: ∫ (s - s0) / s ds
        share[i * k + j] = w - s0 * std::log((s0 + w) / s0);
    }
  return share;
}

TEST(KernelSampling, TriangleIsUniformOverItsArea) {
  constexpr size_t kSamples = 500000;
  constexpr int kGrid = 16;
  TestKernel kernel(kTriangleSource, "triangle_test.cl", "triangle");
  std::vector<float> out = kernel.sample(0, uniforms(2 * kSamples, 7), 1, 2, kSamples);

  std::vector<double> observed(kGrid * kGrid + 1, 0.0);  // the last cell: outside
  for (size_t i = 0; i < kSamples; ++i) {
    int c = triangle_cell(out[2 * i], out[2 * i + 1], kGrid);
    observed[c < 0 ? kGrid * kGrid : c] += 1;
  }
  std::vector<double> expected = triangle_cell_area(kGrid),
                      wrong = triangle_cell_without_sqrt(kGrid);
  double wrong_total = std::accumulate(wrong.begin(), wrong.end(), 0.0);
  EXPECT_NEAR(wrong_total, 1.0, 1e-9);
  for (double& e : expected) e *= kSamples;
  for (double& e : wrong) e *= kSamples;
  expected.push_back(0), wrong.push_back(0);
  expect_fits("triangle", observed, expected);
  expect_rejects("triangle", observed, wrong);
}

// ---------------------------------------------------------------------------------------------
// Next-event estimation: a light triangle by power, a uniform point on it.

const char* const kLightSource = R"(
#include "lights/lights.h"
__kernel void light(__global const KTriangle* tris, __global const int* light_tri,
                    __global const float* light_cdf, int light_count,
                    __global const float* emitter_area_pdf, __global const float* x_in,
                    __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  LightPoint p = sample_light(tris, light_tri, light_cdf, light_count, u[3 * i], u[3 * i + 1],
                              u[3 * i + 2]);
  float3 to_x = (float3)(x_in[0], x_in[1], x_in[2]) - p.position;
  float dist = length(to_x);
  __global float* o = out + 8 * i;
  o[0] = p.position.x;
  o[1] = p.position.y;
  o[2] = p.position.z;
  o[3] = p.normal.x;
  o[4] = p.normal.y;
  o[5] = p.normal.z;
  o[6] = (float)p.emitter;
  o[7] = light_pdf_solid_angle(emitter_area_pdf, p.emitter, dist, dot(p.normal, to_x) / dist);
}
)";

TEST(KernelSampling, LightsByPowerAndUniformOnEach) {
  constexpr size_t kSamples = 300000;
  constexpr int kGrid = 8;  // barycentric cells per triangle
  // Two emitters (band-integrated radiance), three emitting triangles in different planes among
  // non-emitting ones: areas 0.5, 2 and 1.2, powers 0.5π, 0.7π and 1.2π.
  const std::vector<double> radiance = {1.0, 0.35};
  std::vector<KTriangle> tris = {
      triangle({5, 5, 5}, {6, 5, 5}, {5, 6, 5}, -1, 0),
      triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 0, 1),  // z = 1, facing +z
      triangle({5, 5, 6}, {6, 5, 6}, {5, 6, 6}, -1, 2),
      triangle({2, 0, 0}, {2, 2, 0}, {2, 0, 2}, 1, 3),        // x = 2, facing +x
      triangle({0, -1, 0}, {0, -1, 2}, {1.2, -1, 0}, 0, 4)};  // y = -1, facing +y
  const std::vector<int> light_tri = {1, 3, 4};
  const int lights = static_cast<int>(light_tri.size());
  std::vector<Vector3d> v0(lights), e1(lights), e2(lights), normal(lights);
  std::vector<double> area(lights), power(lights);
  double total = 0, total_area = 0;
  for (int j = 0; j < lights; ++j) {
    const KTriangle& t = tris[light_tri[j]];
    v0[j] = Vector3d(t.v0[0], t.v0[1], t.v0[2]);
    e1[j] = Vector3d(t.v1[0], t.v1[1], t.v1[2]) - v0[j];
    e2[j] = Vector3d(t.v2[0], t.v2[1], t.v2[2]) - v0[j];
    normal[j] = e1[j].cross(e2[j]).normalized();
    area[j] = 0.5 * e1[j].cross(e2[j]).norm();
    power[j] = area[j] * M_PI * radiance[t.emitter];
    total += power[j], total_area += area[j];
  }
  std::vector<float> light_cdf, emitter_area_pdf;
  double cdf = 0;
  for (double p : power) light_cdf.push_back(static_cast<float>((cdf += p) / total));
  light_cdf.back() = 1.0f;
  for (double r : radiance) emitter_area_pdf.push_back(static_cast<float>(M_PI * r / total));
  const Vector3d x(1, 0.5, 1.5);  // sees the fronts of triangles 1 and 4, the back of 3

  TestKernel kernel(kLightSource, "light_test.cl", "light");
  kernel.input(0, tris);
  kernel.input(1, light_tri);
  kernel.input(2, light_cdf);
  kernel.scalar(3, lights);
  kernel.input(4, emitter_area_pdf);
  kernel.input(5, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
  std::vector<float> out = kernel.sample(6, uniforms(3 * kSamples, 42), 7, 8, kSamples);

  const int cells = kGrid * kGrid;
  std::vector<double> observed(lights * cells + 1, 0.0), chosen(lights, 0.0);
  size_t unmatched = 0, bad_normal = 0, bad_emitter = 0, bad_pdf = 0;
  for (size_t i = 0; i < kSamples; ++i) {
    const Vector3d p = at(out, 8 * i), n = at(out, 8 * i + 3);
    // The light the point lies on: its barycentrics by least squares, the residual ~0.
    int found = -1, cell = -1;
    for (int j = 0; j < lights && found < 0; ++j) {
      Eigen::Matrix<double, 3, 2> a;
      a << e1[j], e2[j];
      Eigen::Vector2d b = a.colPivHouseholderQr().solve(p - v0[j]);
      if ((a * b - (p - v0[j])).norm() > 1e-5) continue;
      cell = triangle_cell(b[0], b[1], kGrid);
      if (cell >= 0) found = j;
    }
    if (found < 0) {
      ++unmatched;
      observed.back() += 1;
      continue;
    }
    chosen[found] += 1;
    observed[found * cells + cell] += 1;
    const KTriangle& t = tris[light_tri[found]];
    if ((n - normal[found]).norm() > 1e-5) ++bad_normal;
    if (out[8 * i + 6] != float(t.emitter)) ++bad_emitter;
    // Solid-angle density from x: p(triangle) / area · dist² / cos at the light, 0 from behind.
    const Vector3d to_x = x - p;
    const double dist = to_x.norm(), cos_light = normal[found].dot(to_x) / dist;
    const double want =
        cos_light > 0 ? power[found] / total / area[found] * dist * dist / cos_light : 0;
    if (std::abs(out[8 * i + 7] - want) > 1e-4 * want) ++bad_pdf;
  }
  EXPECT_EQ(unmatched, 0u) << "points on no light triangle";
  EXPECT_EQ(bad_normal, 0u);
  EXPECT_EQ(bad_emitter, 0u);
  EXPECT_EQ(bad_pdf, 0u) << "light_pdf_solid_angle";

  const std::vector<double> share = triangle_cell_area(kGrid);
  std::vector<double> expected(observed.size(), 0.0), wrong(observed.size(), 0.0);
  std::vector<double> expected_choice(lights), wrong_choice(lights);
  for (int j = 0; j < lights; ++j) {
    expected_choice[j] = kSamples * power[j] / total;
    wrong_choice[j] = kSamples * area[j] / total_area;  // by area instead of power
    for (int c = 0; c < cells; ++c) {
      expected[j * cells + c] = expected_choice[j] * share[c];
      wrong[j * cells + c] = wrong_choice[j] * share[c];
    }
  }
  expect_fits("light choice", chosen, expected_choice);
  expect_rejects("light choice", chosen, wrong_choice);
  expect_fits("light points", observed, expected);
  expect_rejects("light points", observed, wrong);
}

}  // namespace

// The p-values against known points of the χ² distribution.
TEST(KernelSamplingChi2, PValuesOfTheChi2Distribution) {
  EXPECT_NEAR(gamma_q(1.0, 3.0), std::exp(-3.0), 1e-12);  // df 2: e^(-x/2)
  EXPECT_NEAR(gamma_q(5.0, 18.307 / 2), 0.05, 1e-4);      // df 10, the 95% point
  EXPECT_NEAR(gamma_q(0.5, 6.634897 / 2), 0.01, 1e-6);    // df 1, the 99% point
  EXPECT_NEAR(gamma_q(50.0, 124.342 / 2), 0.05, 1e-4);    // df 100, the 95% point
  EXPECT_NEAR(gamma_q(50.0, 77.929 / 2), 0.95, 1e-4);     // df 100, the 5% point
  Chi2 r = chi2_test({10, 20, 30, 0}, {20, 20, 20, 0});
  EXPECT_EQ(r.df, 2);
  EXPECT_NEAR(r.statistic, 10.0, 1e-12);
  EXPECT_NEAR(r.p, std::exp(-5.0), 1e-12);
  EXPECT_EQ(chi2_test({10, 20, 29, 1}, {20, 20, 20, 0}).p, 0.0);  // a sample where p = 0
}
