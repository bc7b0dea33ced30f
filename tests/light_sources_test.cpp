// Point, spot, distant and infinite lights (docs/lights.md) against ground truth computed here in
// double: a grey Lambert floor (ρ = 0.5) under one light, seen from above, has the radiance
// ρ/π·E(x) where E is the irradiance the light gives the point x — I·cos θ/d² for a point, the
// same times pbrt-v4's smoothstep falloff for a spot, E₀·cos θ for a distant light, π·L for a
// constant infinite light over the upper hemisphere, Σ L cos θ dω over an environment image's
// texels (latitude-longitude and equal-area). The truth is averaged over each pixel (16×16
// points), as the film's box filter averages it. Every integrator is held to it: backward and
// photon mapping (next-event estimation, MIS with BSDF sampling for the infinite light) and
// forward (photons from the light). The residuals' mean in rings about the image centre must be
// within 4 standard errors (of the residuals themselves) and 1 % of the truth there.
// Also: the χ² fit of the spot cone and the uniform sphere on the device.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "analytic_floor.h"
#include "chi2.h"
#include "color/color_space.h"
#include "image/exr_io.h"
#include "kernel_harness.h"
#include "render_support.h"
#include "spectrum/rgb_spectrum.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

double smoothstep(double x, double a, double b) {
  double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

constexpr double kRho = 0.5;
const char* const kGrey = R"({"passive": {"reflectance": 0.5}})";

// Irradiance per unit of the light's spectrum at a floor point, in bin i of the scene.
using Irradiance = std::function<double(const Scene&, const Vector3d&, int)>;

void expect_lit_floor(const std::string& name, const std::string& light,
                      const std::string& integrator, const Irradiance& irradiance, int spp,
                      long long photons, int passes) {
  expect_floor(
      floor_scene(name, kGrey, light), integrator,
      [&](const Scene& sc, const Vector3d& x, int i) { return kRho / M_PI * irradiance(sc, x, i); },
      spp, photons, passes);
}

struct LightCase {
  const char* name;
  std::string light;
  Irradiance irradiance;
  std::function<void()> prepare = [] {};  // writes the files the light reads
};

// A light's own value in bin i (its spectrum times its scale).
double light_value(const Scene& scene, int i) {
  return scene.lights.front().per_bin[i];
}

// ---------------------------------------------------------------------------------------------
// Environment images, made here: a sky whose colour varies with the zenith angle and the
// azimuth, with a bright warm sun; in the latitude-longitude mapping (32 × 16) and in the
// equal-area square (24 × 24), both in the image frame's +z up (the floor's normal).

std::array<double, 3> sky_rgb(const Vector3d& w) {
  double phi = std::atan2(w.y(), w.x()), up = std::max(w.z(), 0.0);
  std::array<double, 3> rgb = {0.2 + 0.1 * std::cos(phi), 0.3 + 0.2 * up, 0.6 + 0.3 * up};
  if (w.z() < 0) rgb = {0.05, 0.04, 0.03};  // the ground below the horizon
  // The sun: 20 times brighter within 20° of (0.5, 0.3, 0.81).
  if (w.dot(Vector3d(0.5, 0.3, 0.81).normalized()) > std::cos(20 * M_PI / 180))
    rgb = {8.0, 6.5, 4.0};
  return rgb;
}

// Clarberg's equal-area square → sphere, as pbrt-v4 writes it (the test's own copy).
Vector3d equal_area_to_sphere(double px, double py) {
  double u = 2 * px - 1, v = 2 * py - 1, up = std::abs(u), vp = std::abs(v);
  double sd = 1 - (up + vp), d = std::abs(sd), r = 1 - d;
  double phi = (r == 0 ? 1 : (vp - up) / r + 1) * M_PI / 4;
  double z = std::copysign(1 - r * r, sd);
  double cp = std::copysign(std::cos(phi), u), sp = std::copysign(std::sin(phi), v);
  double q = r * std::sqrt(std::max(0.0, 2 - r * r));
  return {cp * q, sp * q, z};
}

// Its inverse (pbrt-v4's EqualAreaSphereToSquare, with atan in place of its polynomial).
std::pair<double, double> sphere_to_equal_area(const Vector3d& d) {
  double x = std::abs(d.x()), y = std::abs(d.y()), z = std::abs(d.z());
  double r = std::sqrt(std::max(0.0, 1 - z)), a = std::max(x, y), b = std::min(x, y);
  b = a == 0 ? 0 : b / a;
  double phi = std::atan(b) * 2 / M_PI;
  if (x < y) phi = 1 - phi;
  double v = phi * r, u = r - v;
  if (d.z() < 0) {
    std::swap(u, v);
    u = 1 - u;
    v = 1 - v;
  }
  u = std::copysign(u, d.x());
  v = std::copysign(v, d.y());
  return {0.5 * (u + 1), 0.5 * (v + 1)};
}

Vector3d latlong_to_sphere(double u, double v) {
  double theta = v * M_PI, phi = u * 2 * M_PI;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct Environment {
  int width, height;
  bool equal_area;
  std::string file;
  // The file's content: the sky, one grey (a furnace), or the sky with its rows in reverse order
  // (a latitude-longitude image flipped top to bottom: the sky mirrored in z).
  enum class Content { sky, grey, flipped_sky } content = Content::sky;
  // The world's z of a texel's direction: −1 under a light transform that mirrors z.
  double world_z = 1;
  Vector3d direction(double u, double v) const {
    return equal_area ? equal_area_to_sphere(u, v) : latlong_to_sphere(u, v);
  }
};

// The environment image's path (under the tests' scratch folder) and how it maps.
Environment environment(const std::string& name, bool equal_area) {
  return {equal_area ? 24 : 32, equal_area ? 24 : 16, equal_area,
          std::string(KASHA_TEST_TMP) + "/environments/" + name + ".exr"};
}

// Writes the sky at the texel centres as an EXR (linear sRGB through its XYZ layer).
void write_environment(const Environment& env) {
  Image img;
  img.width = env.width;
  img.height = env.height;
  for (int y = 0; y < env.height; ++y)
    for (int x = 0; x < env.width; ++x) {
      const double row = env.content == Environment::Content::flipped_sky ? env.height - 1 - y : y;
      std::array<double, 3> rgb =
          env.content == Environment::Content::grey
              ? std::array<double, 3>{0.6, 0.6, 0.6}
              : sky_rgb(env.direction((x + 0.5) / env.width, (row + 0.5) / env.height));
      Vec3d xyz = linear_srgb_to_xyz({rgb[0], rgb[1], rgb[2]});
      for (int k = 0; k < 3; ++k) img.xyz.push_back(static_cast<float>(xyz[k]));
    }
  std::filesystem::create_directories(std::filesystem::path(env.file).parent_path());
  write_exr(env.file, img);
}

// The irradiance of the floor (normal +z) under the image: Σ over texels of L_t cos θ dω, each
// texel's solid angle integrated over 8 × 8 sub-directions (the truth, in double, from the
// image the renderer reads back and the RGB → spectrum it uses for texels).
double environment_irradiance(const Scene& scene, const Environment& env, int bin) {
  static std::map<std::string, std::vector<double>> cache;
  auto& e = cache[env.file + std::to_string(scene.grid.bins)];
  if (e.empty()) {
    const Light& l = scene.lights.front();
    const RgbImage& img = l.environment->image;
    e.assign(scene.grid.bins, 0.0);
    constexpr int kSub = 8;
    for (int y = 0; y < env.height; ++y)
      for (int x = 0; x < env.width; ++x) {
        const float* p = img.at(x, y);
        double scale;
        SigmoidCoefficients c = rgb_unbounded_sigmoid({p[0], p[1], p[2]}, &scale);
        double projected = 0;  // ∫ max(cos θ, 0) dω over the texel
        for (int a = 0; a < kSub; ++a)
          for (int b = 0; b < kSub; ++b) {
            double u = (x + (a + 0.5) / kSub) / env.width, v = (y + (b + 0.5) / kSub) / env.height;
            double jac = env.equal_area ? 4 * M_PI : 2 * M_PI * M_PI * std::sin(v * M_PI);
            projected += std::max(env.world_z * env.direction(u, v).z(), 0.0) * jac /
                         (double(env.width) * env.height * kSub * kSub);
          }
        if (scale > 0)
          for (int i = 0; i < scene.grid.bins; ++i)
            e[i] += projected * scale * sigmoid_spectrum(c, scene.grid.center(i)) * l.per_bin[i];
      }
  }
  return e[bin];
}

const std::vector<LightCase>& light_cases() {
  static std::vector<LightCase> cases;
  if (!cases.empty()) return cases;
  cases.push_back({"point", R"({"type": "point", "position": [0.3, 0.2, 1.2], "intensity": 2})",
                   [](const Scene& sc, const Vector3d& x, int i) {
                     Vector3d to = Vector3d(0.3, 0.2, 1.2) - x;
                     double d = to.norm();
                     return light_value(sc, i) * to.z() / d / (d * d);
                   }});
  cases.push_back(
      {"spot",
       R"({"type": "spot", "from": [0, 0, 2], "to": [0.2, 0, 0], "intensity": 3, "cone_deg": 30, "cone_delta_deg": 15})",
       [](const Scene& sc, const Vector3d& x, int i) {
         Vector3d p(0, 0, 2), axis = (Vector3d(0.2, 0, 0) - p).normalized(), to = p - x;
         double d = to.norm();
         double c = (-to / d).dot(axis);
         return light_value(sc, i) * to.z() / d / (d * d) *
                smoothstep(c, std::cos(30 * M_PI / 180), std::cos(15 * M_PI / 180));
       }});
  cases.push_back(
      {"distant", R"({"type": "distant", "from": [1, 0.5, 2], "to": [0, 0, 0], "irradiance": 1.5})",
       [](const Scene& sc, const Vector3d&, int i) {
         return light_value(sc, i) * Vector3d(1, 0.5, 2).normalized().z();
       }});
  cases.push_back(
      {"infinite", R"({"type": "infinite", "radiance": 0.7})",
       [](const Scene& sc, const Vector3d&, int i) { return light_value(sc, i) * M_PI; }});
  for (bool equal_area : {false, true}) {
    const char* name = equal_area ? "sky_equal_area" : "sky_latlong";
    Environment env = environment(name, equal_area);
    cases.push_back({name,
                     std::string(R"({"type": "infinite", "image": ")") + env.file +
                         R"(", "mapping": ")" + (equal_area ? "equal_area" : "latlong") +
                         R"(", "scale": 0.5})",
                     [env](const Scene& sc, const Vector3d&, int i) {
                       return environment_irradiance(sc, env, i);
                     },
                     [env] { write_environment(env); }});
  }
  // Under any invertible transform pbrt-v4's way (directions mapped, then normalised): the sky
  // flipped top to bottom (its sun below the horizon) under a mirror in z renders as the upright
  // sky does without one (its truth, with the texels' directions mirrored, is sky_latlong's),
  // and a grey image under a shear and an uneven scale is still a furnace (π·L on the floor).
  auto add = [](const char* name, Environment env, const std::string& transform) {
    cases.push_back({name,
                     std::string(R"({"type": "infinite", "image": ")") + env.file +
                         R"(", "mapping": ")" + (env.equal_area ? "equal_area" : "latlong") +
                         R"(", "scale": 0.5, "transform": )" + transform + "}",
                     [env](const Scene& sc, const Vector3d&, int i) {
                       return environment_irradiance(sc, env, i);
                     },
                     [env] { write_environment(env); }});
  };
  Environment mirrored = environment("sky_flipped_mirrored", false);
  mirrored.content = Environment::Content::flipped_sky;
  mirrored.world_z = -1;
  add("sky_flipped_mirrored", mirrored, R"({"scale": [1, 1, -1]})");
  Environment grey = environment("grey_sheared", true);
  grey.content = Environment::Content::grey;
  add("grey_sheared", grey,
      R"({"matrix": [1, 0.8, 0, 0, 0, 0.5, 0.3, 0, 0.2, 0, 2, 0, 0, 0, 0, 1]})");
  return cases;
}

class LightSources : public ::testing::TestWithParam<int> {};

TEST_P(LightSources, BackwardMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  c.prepare();
  expect_lit_floor(c.name, c.light, "backward", c.irradiance, 16, 0, 1);
}

TEST_P(LightSources, PhotonMappingMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  c.prepare();
  expect_lit_floor(c.name, c.light, "photon", c.irradiance, 16, 1 << 14, 1);
}

TEST_P(LightSources, ForwardMatchesTheAnalyticFloor) {
  const LightCase& c = light_cases()[GetParam()];
  c.prepare();
  expect_lit_floor(c.name, c.light, "forward", c.irradiance, 0, 1 << 18, 2);
}

INSTANTIATE_TEST_SUITE_P(Lights, LightSources, ::testing::Range(0, 8),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(light_cases()[info.param].name);
                         });

// ---------------------------------------------------------------------------------------------
// An area lamp low over the floor and off to its side, so most of the floor sees it at grazing
// angles: the irradiance of a Lambertian polygon is exact (Lambert's formula: (L/2)·Σ over its
// edges of the angle each subtends times its normal's component along the floor's normal).
// Shadow rays to light points met at grazing angles once stopped too late and hit the lamp
// itself: backward and photon mapping showed 20 % too little light here.

double polygon_irradiance(const Vector3d& x, const std::vector<Vector3d>& polygon,
                          double radiance) {
  double sum = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    Vector3d a = (polygon[i] - x).normalized(),
             b = (polygon[(i + 1) % polygon.size()] - x).normalized();
    Vector3d g = a.cross(b);
    if (g.norm() == 0) continue;
    sum += std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * g.normalized().z();
  }
  return radiance / 2 * std::abs(sum);
}

TEST(AreaLamp, AtGrazingAnglesEveryIntegratorMatchesTheAnalyticFloor) {
  const std::string scene = floor_scene(
      "grazing", R"({"passive": {"reflectance": 0.5}}, "black": {})", "", "", "",
      R"({"type": "quad", "corner": [1.6, -1, 0.4], "u": [0, 2, 0], "v": [1, 0, 0], "material": "black",
          "emission": 2})");
  // Beyond the camera's view of the floor (its rays to x = 1.73 cross z = 0.4 at x = 1.5).
  const std::vector<Vector3d> lamp = {{1.6, -1, 0.4}, {1.6, 1, 0.4}, {2.6, 1, 0.4}, {2.6, -1, 0.4}};
  auto radiance = [&](const Scene&, const Vector3d& x, int) {
    return kRho / M_PI * polygon_irradiance(x, lamp, 2.0);
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "photon", radiance, 16, 1 << 14, 1);
  // Light tracing reaches the far floor through few, steep photons: more passes.
  expect_floor(scene, "forward", radiance, 0, 1 << 18, 8);
}

// ---------------------------------------------------------------------------------------------
// χ² of the spot cone's photon directions and of the uniform sphere, on the device.

const char* const kSpotSource = R"(
#include "lights/lights.h"
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
    cone[cell_of(d.dot(axis), ct, 1, kCos) * kPhi + cell_of(azimuth(d, s, t), 0, 2 * M_PI, kPhi)] +=
        1;
    double phi = std::atan2(z.y(), z.x());
    sphere[cell_of(z.z(), -1, 1, kCos) * kPhi +
           cell_of(phi < 0 ? phi + 2 * M_PI : phi, 0, 2 * M_PI, kPhi)] += 1;
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
      expected_cone[a * kPhi + b] = expected_sphere[a * kPhi + b] =
          double(kSamples) / (kCos * kPhi);
      wrong_cone[a * kPhi + b] = kSamples * (ct + (1 - ct) * (a + 0.5) / kCos) / wc / kPhi;
      wrong_sphere[a * kPhi + b] = kSamples * (1.5 + (-1 + 2 * (a + 0.5) / kCos)) / ws / kPhi;
    }
  expect_fits("spot cone", cone, expected_cone);
  expect_rejects("spot cone, cosine-weighted", cone, wrong_cone);
  expect_fits("uniform sphere", sphere, expected_sphere);
  expect_rejects("sphere denser towards +z", sphere, wrong_sphere);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// χ² of the environment image's sampling on the device: directions binned by the texel they fall
// in (the test's own inverse mappings) against each texel's share of the image's power (mean RGB
// times solid angle, computed here); the density the kernel reports, and the one env_pdf gives
// the same direction, against that share; and an image of one colour sampled in the equal-area
// mapping, binned in equal cells of cos θ and φ, must be uniform over the sphere.

namespace {

const char* const kEnvironmentSource = R"(
#include "lights/environment.h"
__kernel void env(__global const KLight* l, __global const float* spectra, __global const float* u,
                  __global float* out) {
  size_t i = get_global_id(0);
  SceneView s;
  s.spectra = spectra;
  int texel;
  float pdf;
  float3 w = env_sample(&s, l, (float2)(u[2 * i], u[2 * i + 1]), &texel, &pdf);
  vstore3(w, 0, out + 5 * i);
  out[5 * i + 3] = pdf;
  out[5 * i + 4] = env_pdf(&s, l, w);
}
)";

struct EnvSamples {
  std::vector<float> out;
  size_t n;
};

// Samples the image rgb (width × height, 3 floats a texel) through the kernel.
EnvSamples sample_environment(const std::vector<float>& rgb, int width, int height, bool equal_area,
                              size_t n, std::uint32_t seed,
                              const Eigen::Matrix3d& to_light = Eigen::Matrix3d::Identity()) {
  EnvironmentImage env;
  env.image.width = width;
  env.image.height = height;
  env.image.rgb = rgb;
  env.mapping = equal_area ? EnvironmentMapping::equal_area : EnvironmentMapping::latlong;
  WavelengthGrid grid = choose_grid(GridRequest{}, {}, {});
  EnvironmentData d = environment_data(env, std::vector<double>(grid.bins, 1.0), grid);
  KLight l{};
  l.type = KASHA_LIGHT_INFINITE;
  l.width = width;
  l.height = height;
  l.mapping = equal_area ? KASHA_MAPPING_EQUAL_AREA : KASHA_MAPPING_LATLONG;
  for (int k = 0; k < 9; ++k) l.to_light[k] = static_cast<float>(to_light(k / 3, k % 3));
  l.general = to_light.isIdentity() ? 0 : 1;
  l.image = 0;
  std::vector<float> spectra = d.texels;
  l.distribution = static_cast<int>(spectra.size());
  spectra.insert(spectra.end(), d.distribution.begin(), d.distribution.end());
  KernelDefines defines = test_kernel_defines();
  defines["KASHA_ENVIRONMENT"] = "1";
  TestKernel kernel(kEnvironmentSource, "env_test.cl", "env", defines);
  kernel.input(0, std::vector<KLight>{l});
  kernel.input(1, spectra);
  return {kernel.sample(2, uniforms(2 * n, seed), 3, 5, n), n};
}

TEST(LightSampling, EnvironmentImagesFitTheirDensities) {
  for (bool equal_area : {false, true}) {
    SCOPED_TRACE(equal_area ? "equal-area" : "latitude-longitude");
    const int W = equal_area ? 12 : 16, H = equal_area ? 12 : 8;
    const Environment geometry{W, H, equal_area, ""};
    std::vector<float> rgb;
    std::uint32_t state = 12345;
    for (int t = 0; t < W * H; ++t)
      for (int k = 0; k < 3; ++k) {
        state = state * 1664525u + 1013904223u;
        rgb.push_back(0.05f + (state >> 8) * (1.0f / 16777216.0f) * (t % 7 == 0 ? 5.0f : 1.0f));
      }
    const size_t n = 300000;
    EnvSamples s = sample_environment(rgb, W, H, equal_area, n, equal_area ? 5 : 6);
    // The texel's solid angle and share of power, computed here.
    std::vector<double> omega(W * H), share(W * H), observed(W * H, 0), wrong(W * H);
    double total = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        omega[y * W + x] =
            equal_area ? 4 * M_PI / (W * H)
                       : 2 * M_PI / W * (std::cos(M_PI * y / H) - std::cos(M_PI * (y + 1) / H));
        const float* p = &rgb[3 * (y * W + x)];
        share[y * W + x] = (p[0] + p[1] + p[2]) / 3.0 * omega[y * W + x];
        total += share[y * W + x];
      }
    size_t bad_pdf = 0;
    for (size_t i = 0; i < n; ++i) {
      Vector3d w = at(s.out, 5 * i);
      // The texel by the test's own inverse mapping.
      int t = 0;
      if (!equal_area) {
        double phi = std::atan2(w.y(), w.x());
        if (phi < 0) phi += 2 * M_PI;
        int x = std::min(W - 1, int(phi / (2 * M_PI) * W));
        int y = std::min(H - 1, int(std::acos(std::clamp(w.z(), -1.0, 1.0)) / M_PI * H));
        t = y * W + x;
      } else {
        auto [u, v] = sphere_to_equal_area(w);
        t = std::min(H - 1, int(v * H)) * W + std::min(W - 1, int(u * W));
      }
      observed[t] += 1;
      // The density is the texel's share over its solid angle at the texel's centre (latitude-
      // longitude varies with sin θ inside a texel: compared at the sample's own θ).
      double jac = 1;
      if (!equal_area) {
        double y0 = t / W, sin_t = std::hypot(w.x(), w.y());
        jac = (std::cos(M_PI * y0 / H) - std::cos(M_PI * (y0 + 1) / H)) / (M_PI / H * sin_t);
      }
      double want = share[t] / total / omega[t] * jac;
      if (std::abs(s.out[5 * i + 3] - want) > 2e-3 * want ||
          std::abs(s.out[5 * i + 4] - s.out[5 * i + 3]) > 2e-3 * want)
        ++bad_pdf;
    }
    // A sample within float rounding of a texel's edge may bin into the neighbour here.
    EXPECT_LE(bad_pdf, n / 10000) << "densities off the texel's share";
    std::vector<double> expected(W * H);
    for (int t = 0; t < W * H; ++t) {
      expected[t] = n * share[t] / total;
      wrong[t] = n * omega[t] / (4 * M_PI);  // uniform over the sphere: ignores the image
    }
    expect_fits(equal_area ? "equal-area texels" : "latitude-longitude texels", observed, expected);
    expect_rejects(equal_area ? "equal-area, uniform sphere" : "latitude-longitude, uniform sphere",
                   observed, wrong);
  }
  // One colour, equal-area: uniform over the sphere, in cells of cos θ × φ.
  const int W = 8;
  EnvSamples s = sample_environment(std::vector<float>(3 * W * W, 0.5f), W, W, true, 200000, 9);
  constexpr int kCos = 10, kPhi = 12;
  std::vector<double> observed(kCos * kPhi, 0), expected(kCos * kPhi), wrong(kCos * kPhi);
  for (size_t i = 0; i < s.n; ++i) {
    Vector3d w = at(s.out, 5 * i);
    double phi = std::atan2(w.y(), w.x());
    observed[cell_of(w.z(), -1, 1, kCos) * kPhi +
             cell_of(phi < 0 ? phi + 2 * M_PI : phi, 0, 2 * M_PI, kPhi)] += 1;
  }
  double ws = 0;
  for (int a = 0; a < kCos; ++a) ws += 1.5 + (-1 + 2 * (a + 0.5) / kCos);
  for (int a = 0; a < kCos; ++a)
    for (int b = 0; b < kPhi; ++b) {
      expected[a * kPhi + b] = double(s.n) / (kCos * kPhi);
      wrong[a * kPhi + b] = s.n * (1.5 + (-1 + 2 * (a + 0.5) / kCos)) / ws / kPhi;
    }
  expect_fits("equal-area square, one colour", observed, expected);
  expect_rejects("equal-area, denser towards +z", observed, wrong);
}

// Under a general map M (world to the image's frame, normalised after it) one colour is drawn
// with the density (1/4π)·|det M|/|M w|³ (the solid-angle Jacobian of w ↦ Mw/|Mw|): each sample's
// reported density and env_pdf's match it, and the directions fit it in cells of cos θ × φ.
TEST(LightSampling, AGeneralEnvironmentTransformKeepsItsDensityConsistent) {
  Eigen::Matrix3d m;
  m << 1, 0.8, 0, 0, 0.5, 0.3, 0.2, 0, 2;
  const Eigen::Matrix3d to_light = m.inverse();
  const int W = 8;
  const size_t n = 200000;
  EnvSamples s = sample_environment(std::vector<float>(3 * W * W, 0.5f), W, W, true, n, 11, to_light);
  auto density = [&](const Vector3d& w) {
    return std::abs(to_light.determinant()) / std::pow((to_light * w).norm(), 3) / (4 * M_PI);
  };
  constexpr int kCos = 10, kPhi = 12;
  std::vector<double> observed(kCos * kPhi, 0), expected(kCos * kPhi, 0), uniform(kCos * kPhi);
  size_t bad_pdf = 0;
  for (size_t i = 0; i < n; ++i) {
    Vector3d w = at(s.out, 5 * i);
    const double want = density(w);
    if (std::abs(s.out[5 * i + 3] - want) > 2e-3 * want ||
        std::abs(s.out[5 * i + 4] - want) > 2e-3 * want)
      ++bad_pdf;
    double phi = std::atan2(w.y(), w.x());
    observed[cell_of(w.z(), -1, 1, kCos) * kPhi +
             cell_of(phi < 0 ? phi + 2 * M_PI : phi, 0, 2 * M_PI, kPhi)] += 1;
  }
  EXPECT_LE(bad_pdf, n / 100000) << "densities off the map's Jacobian";
  // The expected count of each cell: the density integrated over it (cells are equal in solid
  // angle, 4π / cells, midpoint rule on 16 × 16 points).
  constexpr int kSub = 16;
  for (int a = 0; a < kCos; ++a)
    for (int b = 0; b < kPhi; ++b) {
      double sum = 0;
      for (int i = 0; i < kSub; ++i)
        for (int j = 0; j < kSub; ++j) {
          double z = -1 + 2 * (a + (i + 0.5) / kSub) / kCos;
          double phi = 2 * M_PI * (b + (j + 0.5) / kSub) / kPhi, r = std::sqrt(1 - z * z);
          sum += density({r * std::cos(phi), r * std::sin(phi), z});
        }
      expected[a * kPhi + b] = n * sum / (kSub * kSub) * 4 * M_PI / (kCos * kPhi);
      uniform[a * kPhi + b] = double(n) / (kCos * kPhi);
    }
  expect_fits("general map, one colour", observed, expected);
  expect_rejects("general map drawn as a rotation would be", observed, uniform);
}

}  // namespace
