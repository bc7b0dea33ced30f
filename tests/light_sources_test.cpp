// Point, spot, distant and infinite lights (docs/lights.md) against ground truth computed here in
// double: a grey Lambert floor (ρ = 0.5) under one light, seen from above, has the radiance
// ρ/π·E(x) where E is the irradiance the light gives the point x — I·cos θ/d² for a point, the
// same times pbrt-v4's smoothstep falloff for a spot, E₀·cos θ for a distant light, π·L for a
// constant infinite light over the upper hemisphere. The truth is averaged over each pixel (16×16
// points), as the film's box filter averages it. Every integrator is held to it: backward and
// photon mapping (next-event estimation, MIS with BSDF sampling for the infinite light) and
// forward (photons from the light). The residuals' mean in rings about the image centre must be
// within 4 standard errors (of the residuals themselves) and 1 % of the truth there.
// Also: the χ² fit of the spot cone and the uniform sphere on the device.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "chi2.h"
#include "kernel_harness.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

constexpr double kRho = 0.5;
constexpr int kSize = 24;

std::string floor_scene(const std::string& name, const std::string& light) {
  std::ostringstream s;
  s << R"({"kasha_scene": 1,
  "wavelengths": {"min_nm": 400, "max_nm": 700, "bin_nm": 50},
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 60,
             "width": )"
    << kSize << R"(, "height": )" << kSize << R"(},
  "materials": {"grey": {"passive": {"reflectance": )"
    << kRho << R"(}}},
  "lights": [)" << light
    << R"(],
  "shapes": [{"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "grey"}]
})";
  return write_file(name + ".json", s.str());
}

// The floor point a camera ray through (px + sx, py + sy) hits (the film's pixel mapping).
Vector3d floor_point(const KCamera& c, double x, double y) {
  Vector3d o(c.position[0], c.position[1], c.position[2]);
  Vector3d f(c.forward[0], c.forward[1], c.forward[2]), r(c.right[0], c.right[1], c.right[2]),
      u(c.up[0], c.up[1], c.up[2]);
  Vector3d d = f + (2 * x / c.width - 1) * r + (1 - 2 * y / c.height) * u;
  return o + d * (-o.z() / d.z());
}

// Irradiance per unit of the light's spectrum at a floor point.
using Irradiance = std::function<double(const Vector3d&)>;

// Renders the scene and compares every bin in rings of pixels with ρ/π·E·value.
void expect_floor(const std::string& scene, const std::string& integrator, double value,
                  const Irradiance& irradiance, int spp, long long photons, int passes) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = passes;
  s.integrator_settings.spp = spp;
  s.integrator_settings.photons = photons;
  RenderResult r = render_scene(scene, s);
  const KCamera cam = r.scene.camera.to_kernel();
  const size_t N = r.scene.grid.bins;
  constexpr int kRings = 4;
  std::vector<double> sum(kRings, 0), sum2(kRings, 0), truth(kRings, 0), count(kRings, 0);
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      double want = 0;
      for (int a = 0; a < 16; ++a)
        for (int b = 0; b < 16; ++b)
          want += irradiance(floor_point(cam, px + (a + 0.5) / 16, py + (b + 0.5) / 16)) / 256;
      want *= kRho / M_PI * value;
      double dx = px + 0.5 - kSize / 2.0, dy = py + 0.5 - kSize / 2.0;
      int ring = std::min(kRings - 1, int(std::sqrt(dx * dx + dy * dy) / (kSize / 2.0) * kRings));
      for (size_t i = 0; i < N; ++i) {
        double d = r.image.spectral[(py * kSize + px) * N + i] - want;
        sum[ring] += d;
        sum2[ring] += d * d;
        truth[ring] += want;
        count[ring] += 1;
      }
    }
  for (int k = 0; k < kRings; ++k) {
    double n = count[k], mean = sum[k] / n, var = sum2[k] / n - mean * mean;
    double se = std::sqrt(std::max(var, 0.0) / (n - 1)), t = truth[k] / n;
    std::printf("%s %s ring %d: truth %.5g, residual %+.3g (SE %.2g)\n", scene.c_str(),
                integrator.c_str(), k, t, mean, se);
    EXPECT_LT(std::abs(mean), 4 * se + 0.01 * t)
        << integrator << " ring " << k << ": truth " << t << ", residual " << mean << " ± " << se;
  }
  EXPECT_EQ(r.rejected, 0);
}

double smoothstep(double x, double a, double b) {
  double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

struct LightCase {
  const char* name;
  const char* light;
  double value;
  Irradiance irradiance;
};

const std::vector<LightCase>& light_cases() {
  static const std::vector<LightCase> cases = {
      {"point", R"({"type": "point", "position": [0.3, 0.2, 1.2], "intensity": 2})", 2,
       [](const Vector3d& x) {
         Vector3d to = Vector3d(0.3, 0.2, 1.2) - x;
         double d = to.norm();
         return to.z() / d / (d * d);
       }},
      {"spot",
       R"({"type": "spot", "from": [0, 0, 2], "to": [0.2, 0, 0], "intensity": 3, "cone_deg": 30, "cone_delta_deg": 15})",
       3,
       [](const Vector3d& x) {
         Vector3d p(0, 0, 2), axis = (Vector3d(0.2, 0, 0) - p).normalized(), to = p - x;
         double d = to.norm();
         double c = (-to / d).dot(axis);
         return to.z() / d / (d * d) *
                smoothstep(c, std::cos(30 * M_PI / 180), std::cos(15 * M_PI / 180));
       }},
      {"distant", R"({"type": "distant", "from": [1, 0.5, 2], "to": [0, 0, 0], "irradiance": 1.5})",
       1.5, [](const Vector3d&) { return Vector3d(1, 0.5, 2).normalized().z(); }},
      {"infinite", R"({"type": "infinite", "radiance": 0.7})", 0.7,
       [](const Vector3d&) { return M_PI; }},
  };
  return cases;
}

class LightSources : public ::testing::TestWithParam<int> {};

TEST_P(LightSources, BackwardMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  expect_floor(floor_scene(c.name, c.light), "backward", c.value, c.irradiance, 16, 0, 1);
}

TEST_P(LightSources, PhotonMappingMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  expect_floor(floor_scene(c.name, c.light), "photon", c.value, c.irradiance, 16, 1 << 14, 1);
}

TEST_P(LightSources, ForwardMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  expect_floor(floor_scene(c.name, c.light), "forward", c.value, c.irradiance, 0, 1 << 18, 2);
}

INSTANTIATE_TEST_SUITE_P(Lights, LightSources, ::testing::Range(0, 4),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(light_cases()[info.param].name);
                         });

// ---------------------------------------------------------------------------------------------
// χ² of the spot cone's photon directions and of the uniform sphere, on the device.

const char* const kSpotSource = R"(
#include "lights.h"
__kernel void spot(__global const KLight* l, __global const float* u, __global float* out) {
  size_t i = get_global_id(0);
  float3 d = sample_spot_cone(l, (float2)(u[2 * i], u[2 * i + 1]));
  float3 s = sample_uniform_sphere((float2)(u[2 * i], u[2 * i + 1]));
  vstore3(d, 0, out + 6 * i);
  vstore3(s, 1, out + 6 * i);
}
)";

double azimuth(const Vector3d& d, const Vector3d& s, const Vector3d& t) {
  double phi = std::atan2(d.dot(t), d.dot(s));
  return phi < 0 ? phi + 2 * M_PI : phi;
}

TEST(LightSampling, SpotConeAndSphereFitTheirDensities) {
  constexpr size_t kSamples = 200000;
  constexpr int kCos = 10, kPhi = 12;
  KernelDefines defines = test_kernel_defines();
  defines["KASHA_LIGHT_SOURCES"] = "1";
  defines["KASHA_SPOT_LIGHTS"] = "1";
  TestKernel kernel(kSpotSource, "spot_test.cl", "spot", defines);
  KLight l{};
  l.type = KASHA_LIGHT_SPOT;
  const Vector3d axis = Vector3d(0.3, -0.5, 0.8).normalized();
  for (int c = 0; c < 3; ++c) l.axis[c] = static_cast<float>(axis[c]);
  l.cos_total = std::cos(40 * M_PI / 180);
  l.cos_falloff = std::cos(30 * M_PI / 180);
  kernel.input(0, std::vector<KLight>{l});
  std::vector<float> out = kernel.sample(1, uniforms(2 * kSamples, 77), 2, 6, kSamples);
  Vector3d s, t;
  frame(axis, s, t);
  const double ct = l.cos_total;
  std::vector<double> cone(kCos * kPhi, 0), sphere(kCos * kPhi, 0), expected_cone(kCos * kPhi),
      expected_sphere(kCos * kPhi), wrong_cone(kCos * kPhi), wrong_sphere(kCos * kPhi);
  for (size_t i = 0; i < kSamples; ++i) {
    Vector3d d = at(out, 6 * i), z = at(out, 6 * i + 3);
    // The cone in equal steps of cos θ from cos_total to 1; the sphere in z from -1 to 1.
    cone[cell_of(d.dot(axis), ct, 1, kCos) * kPhi + cell_of(azimuth(d, s, t), 0, 2 * M_PI, kPhi)] += 1;
    double phi = std::atan2(z.y(), z.x());
    sphere[cell_of(z.z(), -1, 1, kCos) * kPhi + cell_of(phi < 0 ? phi + 2 * M_PI : phi, 0, 2 * M_PI, kPhi)] += 1;
  }
  // Uniform densities share samples equally among cells equal in cos θ and φ; the wrong ones
  // weigh cells by cos θ (a cosine-weighted cone; a sphere denser towards +z).
  double wc = 0, ws = 0;
  for (int a = 0; a < kCos; ++a) {
    wc += ct + (1 - ct) * (a + 0.5) / kCos;
    ws += 1.5 + (-1 + 2 * (a + 0.5) / kCos);
  }
  for (int a = 0; a < kCos; ++a)
    for (int b = 0; b < kPhi; ++b) {
      expected_cone[a * kPhi + b] = expected_sphere[a * kPhi + b] = double(kSamples) / (kCos * kPhi);
      wrong_cone[a * kPhi + b] = kSamples * (ct + (1 - ct) * (a + 0.5) / kCos) / wc / kPhi;
      wrong_sphere[a * kPhi + b] = kSamples * (1.5 + (-1 + 2 * (a + 0.5) / kCos)) / ws / kPhi;
    }
  expect_fits("spot cone", cone, expected_cone);
  expect_rejects("spot cone, cosine-weighted", cone, wrong_cone);
  expect_fits("uniform sphere", sphere, expected_sphere);
  expect_rejects("sphere denser towards +z", sphere, wrong_sphere);
}

}  // namespace
