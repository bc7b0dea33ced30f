// Rough dielectrics and conductors (GGX microfacets, kernels/materials/rough_interface.h):
// - χ² tests of their sampling on the device against their own densities, for reflection and
//   refraction from either side, isotropic and anisotropic roughness; each also rejects the
//   density of a roughness 15 % off. The sampled pdf and weight agree with the evaluation.
// - The energy they reflect and transmit: a rough gold floor and a rough glass floor in a uniformly
//   emitting black enclosure, seen from one angle, show the enclosure times the single-scattering
//   albedo ∫ f |cos θi| dωi, computed here by quadrature from pbrt-v4's formulas in double, in
//   every bin, through backward and photon mapping (light tracing meets the camera's 1° patch of
//   floor too rarely to test it this way).
// - Light tracing's connection of a rough surface to the camera (either side of it) against
//   backward: a rough gold floor and a frosted glass slab under a lamp.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <sstream>

#include "chi2.h"
#include "kernel_harness.h"
#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

const char* const kRoughSource = R"(
#include "materials/rough_interface.h"
/* params: wo (3), eta, alpha_x, alpha_y, kind (0 dielectric, 1 conductor), radiance */
__kernel void sample_rough(__global const float* q, __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float3 wo = normalize((float3)(q[0], q[1], q[2]));
  Ggx a = {q[4], q[5]};
  InterfaceSample s;
  bool ok = q[6] == 0.0f ? rough_dielectric_sample(wo, q[3], a, q[7] != 0.0f, u[3 * i], (float2)(u[3 * i + 1], u[3 * i + 2]), &s)
                         : rough_conductor_sample(wo, a, (float2)(u[3 * i + 1], u[3 * i + 2]), &s);
  __global float* o = out + 7 * i;
  if (!ok) {
    for (int k = 0; k < 7; ++k) o[k] = 0.0f;
    return;
  }
  float pdf, cos_m;
  float f = q[6] == 0.0f ? rough_dielectric_eval(wo, s.wi, q[3], a, q[7] != 0.0f, &pdf)
                         : rough_conductor_eval(wo, s.wi, a, &pdf, &cos_m);
  o[0] = s.wi.x, o[1] = s.wi.y, o[2] = s.wi.z;
  o[3] = s.pdf;
  o[4] = s.weight;
  o[5] = pdf;
  o[6] = f;
}
/* The density of sampling each wi (3 floats per item). */
__kernel void pdf_rough(__global const float* q, __global const float* wi, __global float* out) {
  size_t i = get_global_id(0);
  float3 wo = normalize((float3)(q[0], q[1], q[2]));
  Ggx a = {q[4], q[5]};
  float3 w = (float3)(wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]);
  float pdf, cos_m;
  if (q[6] == 0.0f) rough_dielectric_eval(wo, w, q[3], a, q[7] != 0.0f, &pdf);
  else rough_conductor_eval(wo, w, a, &pdf, &cos_m);
  out[i] = pdf;
}
)";

struct RoughCase {
  std::string name;
  Vector3d wo;
  double eta, ax, ay;
  bool conductor;
};

constexpr int kZ = 48, kPhi = 32,
              kQuad = 12;  // cells in cos θ over [−1, 1] and in φ; points per cell side

// Expected counts per cell (and, last, the samples lost) from the density, by midpoint quadrature
// of the device's own pdf over each cell (equal-area in z, φ).
std::vector<double> expected_counts(const RoughCase& c, double alpha_scale, size_t samples) {
  std::vector<float> q = {
      float(c.wo.x()),           float(c.wo.y()),           float(c.wo.z()),           float(c.eta),
      float(c.ax * alpha_scale), float(c.ay * alpha_scale), c.conductor ? 1.0f : 0.0f, 1.0f};
  std::vector<float> wi;
  for (int a = 0; a < kZ; ++a)
    for (int b = 0; b < kPhi; ++b)
      for (int i = 0; i < kQuad; ++i)
        for (int j = 0; j < kQuad; ++j) {
          double z = -1 + 2 * (a + (i + 0.5) / kQuad) / kZ,
                 phi = 2 * M_PI * (b + (j + 0.5) / kQuad) / kPhi;
          double r = std::sqrt(std::max(0.0, 1 - z * z));
          wi.insert(wi.end(), {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)});
        }
  TestKernel kernel(kRoughSource, "rough_test.cl", "pdf_rough");
  kernel.input(0, q);
  kernel.input(1, wi);
  kernel.output(2, wi.size() / 3);
  kernel.run(wi.size() / 3);
  std::vector<float> pdf = kernel.read(2);
  const double cell_area = (2.0 / kZ) * (2 * M_PI / kPhi) / (kQuad * kQuad);
  std::vector<double> e(kZ * kPhi + 1, 0.0);
  double total = 0;
  for (int cell = 0; cell < kZ * kPhi; ++cell) {
    for (int k = 0; k < kQuad * kQuad; ++k) e[cell] += pdf[cell * kQuad * kQuad + k] * cell_area;
    total += e[cell];
  }
  e.back() = std::max(0.0, 1 - total);
  for (double& v : e) v *= samples;
  return e;
}

TEST(RoughInterface, SamplingFitsItsDensityOnTheDevice) {
  constexpr size_t kSamples = 400000;
  const std::vector<RoughCase> cases = {
      {"glass from outside, 40°", Vector3d(std::sin(0.7), 0, std::cos(0.7)), 1.5, 0.3, 0.3, false},
      {"glass from inside, 30°", Vector3d(0.3, std::sin(0.52), -std::cos(0.52)), 1.5, 0.35, 0.35,
       false},
      {"bubble, anisotropic", Vector3d(0.2, -0.5, 0.7), 0.75, 0.2, 0.5, false},
      {"conductor, 60°", Vector3d(std::sin(1.05), 0, std::cos(1.05)), 1, 0.3, 0.3, true},
      {"conductor, anisotropic", Vector3d(0.1, 0.3, 0.9), 1, 0.15, 0.5, true}};
  std::uint32_t seed = 11;
  for (const RoughCase& c : cases) {
    TestKernel kernel(kRoughSource, "rough_test.cl", "sample_rough");
    std::vector<float> q = {
        float(c.wo.x()), float(c.wo.y()), float(c.wo.z()),           float(c.eta),
        float(c.ax),     float(c.ay),     c.conductor ? 1.0f : 0.0f, 1.0f};
    kernel.input(0, q);
    std::vector<float> out = kernel.sample(1, uniforms(3 * kSamples, seed++), 2, 7, kSamples);
    std::vector<double> observed(kZ * kPhi + 1, 0.0);
    const Vector3d wo = Vector3d(q[0], q[1], q[2]).normalized();
    size_t inconsistent = 0;
    for (size_t i = 0; i < kSamples; ++i) {
      const float* o = &out[7 * i];
      if (o[3] == 0.0f) {
        observed.back() += 1;
        continue;
      }
      Vector3d wi(o[0], o[1], o[2]);
      double phi = std::atan2(wi.y(), wi.x());
      if (phi < 0) phi += 2 * M_PI;
      observed[cell_of(wi.z(), -1, 1, kZ) * kPhi + cell_of(phi, 0, 2 * M_PI, kPhi)] += 1;
      // The sampled pdf is the evaluated one, and the weight is f |cos θi| / pdf.
      double pdf = o[3], weight = o[4], pdf_eval = o[5], f = o[6];
      if (std::abs(pdf - pdf_eval) > 2e-3 * pdf + 1e-6 ||
          std::abs(weight - f * std::abs(wi.z()) / pdf) > 2e-3 * weight + 1e-6)
        ++inconsistent;
      (void)wo;
    }
    EXPECT_LE(inconsistent, kSamples / 10000)
        << c.name << ": sampled pdf or weight differs from the evaluation";
    expect_fits(c.name, observed, expected_counts(c, 1.0, kSamples));
    expect_rejects(c.name + " against a roughness 15 % higher", observed,
                   expected_counts(c, 1.15, kSamples));
  }
}

// ---------------------------------------------------------------------------------------------
// The energy a rough interface keeps: ∫ f(wo, wi) |cos θi| dωi by quadrature, from pbrt-v4's
// formulas written out again here (isotropic GGX, Smith G, unpolarized Fresnel, radiance's 1/η'²).

double ggx_d(double alpha, const Vector3d& m) {
  if (m.z() <= 0) return 0;
  double c2 = m.z() * m.z(), t2 = (1 - c2) / c2, e = 1 + t2 / (alpha * alpha);
  return 1 / (M_PI * alpha * alpha * c2 * c2 * e * e);
}
double ggx_lambda(double alpha, const Vector3d& w) {
  double c2 = w.z() * w.z(), t2 = std::max(0.0, 1 - c2) / c2;
  return (std::sqrt(1 + alpha * alpha * t2) - 1) / 2;
}
double fresnel(double cos_i, std::complex<double> m) {
  return fresnel_reference(cos_i, m);
}

// ∫ over the sphere of wi on a (θ, φ) grid fine enough for alpha ≥ 0.5 (wo in the xz plane, z up).
template <class F>
double sphere_integral(F integrand) {
  const int nt = 1600, np = 400;  // φ symmetric about the plane of wo: [0, π] doubled
  double sum = 0;
  for (int i = 0; i < nt; ++i) {
    double t = M_PI * (i + 0.5) / nt, st = std::sin(t), ct = std::cos(t);
    for (int j = 0; j < np; ++j) {
      double p = M_PI * (j + 0.5) / np;
      sum += integrand(Vector3d(st * std::cos(p), st * std::sin(p), ct)) * st;
    }
  }
  return 2 * sum * (M_PI / nt) * (M_PI / np);
}

// A camera 1° wide looking down at the floor (y = 0) at `deg` from its normal.
std::string floor_scene(const std::string& name, const std::string& material, double deg) {
  const double t = deg * M_PI / 180;
  std::ostringstream s;
  s << R"({"kasha_scene": 1,
  "camera": {"position": [0, 1, 0], "look_at": [)"
    << std::sin(t) << ", " << 1 - std::cos(t) << R"(, 0], "fov_deg": 1, "width": 8, "height": 8},
  "materials": {"black": {}, "floor": )"
    << material << R"(},
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 20, "material": "black", "inward": true,
     "emission": {"nm": [380, 780], "value": [1, 2]}},
    {"type": "quad", "corner": [-10, 0, -10], "u": [0, 0, 20], "v": [20, 0, 0], "material": "floor"}]})";
  return write_file(name, s.str());
}

void expect_albedo(const std::string& scene, const std::vector<double>& albedo,
                   const std::string& label) {
  for (const char* integrator : {"backward", "photon"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.passes = 4;
    s.integrator_settings.spp = 64;
    s.integrator_settings.photons = 1 << 18;
    RenderResult r = render_scene(scene, s);
    const std::vector<double>& le = r.scene.emitters.front().per_bin;
    std::vector<double> truth(le.size());
    for (size_t i = 0; i < le.size(); ++i) truth[i] = le[i] * albedo[i];
    expect_bins_match(r, truth, 0.02, label + " " + integrator,
                      IntegratorRegistry::find(integrator).traits.unbiased);
  }
}

TEST(RoughInterface, ARoughGoldFloorKeepsItsSingleScatteringAlbedo) {
  const double roughness = 0.25, alpha = 0.5, deg = 50;  // alpha = sqrt(roughness), pbrt's remap
  const std::string scene =
      floor_scene("rough_gold.json", R"({"conductor": {"metal": "Au", "roughness": 0.25}})", deg);
  Scene sc = load_scene(scene);
  const Material& gold = sc.materials[sc.material_index("floor")];
  ASSERT_TRUE(gold.rough());
  ASSERT_NEAR(gold.roughness.alpha_x, std::sqrt(roughness), 1e-12);
  const Vector3d wo(std::sin(deg * M_PI / 180), 0, std::cos(deg * M_PI / 180));
  std::vector<double> albedo(sc.grid.bins, 0.0);
  // The bin-independent part once per direction, F per bin.
  const int nt = 1600, np = 400;
  for (int a = 0; a < nt; ++a) {
    double t = 0.5 * M_PI * (a + 0.5) / nt, st = std::sin(t), ct = std::cos(t);
    for (int b = 0; b < np; ++b) {
      double p = M_PI * (b + 0.5) / np;
      Vector3d wi(st * std::cos(p), st * std::sin(p), ct);
      Vector3d m = (wi + wo).normalized();
      double g = 1 / (1 + ggx_lambda(alpha, wo) + ggx_lambda(alpha, wi));
      double base = ggx_d(alpha, m) * g / (4 * wo.z() * wi.z()) * wi.z() * st * (0.5 * M_PI / nt) *
                    (M_PI / np) * 2;
      for (int i = 0; i < sc.grid.bins; ++i)
        albedo[i] += base * fresnel(wo.dot(m), {gold.eta_c[i], gold.k_c[i]});
    }
  }
  std::printf("  rough gold at %g°: albedo %.4f at 450 nm, %.4f at 650 nm\n", deg, albedo[7],
              albedo[27]);
  expect_albedo(scene, albedo, "rough gold");
}

TEST(RoughInterface, ARoughGlassFloorKeepsItsSingleScatteringAlbedo) {
  const double eta = 1.5, alpha = 0.5, deg = 40;
  const std::string scene = floor_scene(
      "rough_glass.json",
      R"({"dielectric": {"eta": 1.5, "roughness": 0.5, "remap_roughness": false}})", deg);
  Scene sc = load_scene(scene);
  ASSERT_TRUE(sc.materials[sc.material_index("floor")].rough());
  const Vector3d wo(std::sin(deg * M_PI / 180), 0, std::cos(deg * M_PI / 180));
  const double lo = ggx_lambda(alpha, wo);
  const double albedo = sphere_integral([&](const Vector3d& wi) {
    double g = 1 / (1 + lo + ggx_lambda(alpha, wi));
    if (wi.z() > 0) {  // reflection
      Vector3d m = (wi + wo).normalized();
      return ggx_d(alpha, m) * g * fresnel(wo.dot(m), eta) / (4 * wo.z() * wi.z()) * wi.z();
    }
    // Transmission into the glass (η' = η): the half vector −(η wi + wo), facing up.
    Vector3d m = -(eta * wi + wo).normalized();
    if (m.z() <= 0 || wo.dot(m) <= 0 || wi.dot(m) >= 0) return 0.0;
    double denom = wi.dot(m) + wo.dot(m) / eta;
    double f = ggx_d(alpha, m) * (1 - fresnel(wo.dot(m), eta)) * g *
               std::abs(wi.dot(m) * wo.dot(m) / (denom * denom * wi.z() * wo.z())) / (eta * eta);
    return f * std::abs(wi.z());
  });
  std::printf("  rough glass at %g°: albedo %.4f (reflection and radiance's transmission)\n", deg,
              albedo);
  expect_albedo(scene, std::vector<double>(sc.grid.bins, albedo), "rough glass");
}

// Light tracing evaluates a rough interface towards the camera (on either side of it); backward
// samples it and estimates next events through it. Their images agree region by region,
// within 4 standard errors of their difference, and on the gold floor within 3 %.
TEST(RoughInterface, LightTracingAgreesWithBackwardOnRoughSurfaces) {
  const std::string scene = write_file("rough_pair.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 1.2, 1.6], "look_at": [0, 0.2, 0], "fov_deg": 55, "width": 24, "height": 24},
  "materials": {"black": {}, "gold": {"conductor": {"metal": "Au", "roughness": 0.1}},
                "frost": {"dielectric": {"eta": 1.5, "uroughness": 0.02, "vroughness": 0.1}},
                "grey": {"passive": {"reflectance": 0.5}}},
  "shapes": [
    {"type": "quad", "corner": [-1, 0, -1], "u": [0, 0, 2], "v": [2, 0, 0], "material": "gold"},
    {"type": "quad", "corner": [-1, 0, -1], "u": [2, 0, 0], "v": [0, 1.5, 0], "material": "grey"},
    {"type": "box", "min": [-0.4, 0.3, -0.3], "max": [0.4, 0.36, 0.3], "material": "frost"},
    {"type": "quad", "corner": [-0.3, 1.5, -0.3], "u": [0.6, 0, 0], "v": [0, 0, 0.6], "material": "black",
     "emission": {"blackbody_K": 4000, "scale": 1e-6}}]})");
  RenderSettings b;
  b.spectral = false;
  b.passes = 4;
  b.integrator_settings.spp = 64;
  RenderResult backward = render_scene(scene, b);
  // Light tracing, and bpt and vcm (connections at the rough surfaces, merges not:
  // next-event estimation, light vertices on them, the camera through them), one sample a pixel
  // a pass.
  for (const char* integrator : {"forward", "bpt", "vcm"}) {
    RenderSettings f = b;
    f.integrator = integrator;
    f.integrator_settings.photons = 1 << 19;
    if (std::string(integrator) != "forward") {
      f.passes = 128;
      f.integrator_settings.photons = 1 << 14;
    }
    RenderResult forward = render_scene(scene, f);
    std::map<std::string, std::vector<size_t>> regions =
        primary_hit_regions(forward.scene, forward.scene.camera);
    ASSERT_GE(regions["gold"].size(), 100u);
    ASSERT_GE(regions["frost"].size(), 40u);
    for (const auto& [name, pixels] : regions) {
      BinStats t = pixel_statistics(forward.image, false, pixels);
      BinStats d = difference_statistics(forward.image, backward.image, false, pixels);
      for (int k = 0; k < 3; ++k) {
        std::printf("  %-6s row %d: %s/backward - 1 = %+.2f %% (± %.2f %%)\n", name.c_str(), k, integrator,
                    100 * d.mean[k] / (t.mean[k] - d.mean[k]),
                    100 * d.standard_error[k] / (t.mean[k] - d.mean[k]));
        EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << integrator << " " << name << " row " << k;
        if (name == "gold") {
          EXPECT_LT(std::abs(d.mean[k]), 0.03 * (t.mean[k] - d.mean[k])) << integrator << " " << name << " row " << k;
        }
      }
    }
  }
}

}  // namespace
