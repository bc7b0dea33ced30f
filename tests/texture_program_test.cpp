// Textures of textures (docs/textures.md#textures-of-textures) against ground truth computed here,
// on the floor of tests/analytic_floor.h under a constant sky (its radiance is ρ(x)·L exactly):
// - a mix of a grey and an RGB colour by pbrt-v4's fbm noise of the point in a scaled, turned
//   texture space, clamped to [0, 1] as pbrt-v4 clamps a reflectance: the truth evaluates the
//   noise (shared/perlin_noise.h) at every floor point, in backward, photon mapping and forward;
// - a checkerboard whose squares are textures (pbrt-v4's dots, and a bilerp of numbers);
// - a scale of a spectrum by a windy texture, and marble (pbrt-v4's spline, by its own colours);
// and the errors of a bad texture of textures, each one line naming where.
// The per-class values against pbrt-v4 itself: tests/pbrt_reference_test.cpp's
// procedural_textures scene.
#include "render/texture_program.h"

#include <gtest/gtest.h>

#include <cmath>

#include "analytic_floor.h"
#include "render/device_scene.h"
#include "render_support.h"
#include "shared/texture_program.h"
#include "spectrum/rgb_spectrum.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

constexpr double kL = 0.7;
const char* const kSky = R"({"type": "infinite", "radiance": 0.7})";

Eigen::Vector2d floor_uv(const Vector3d& x) {
  return {(x.x() + 2) / 4, (x.y() + 2) / 4};
}

// The RGB colour's spectrum averaged over bin i.
double rgb_bin(const std::array<double, 3>& rgb, const Scene& sc, int i) {
  RgbReflectanceSpectrum s(rgb);
  return s.integral(sc.grid.lo(i), sc.grid.hi(i)) / sc.grid.bin_nm;
}

// A texture-space point: the world point by the inverse of scale 0.7 then a turn of 30° about z.
Vector3d noise_space(const Vector3d& x) {
  Eigen::Affine3d world_from_texture = Eigen::Affine3d::Identity();
  world_from_texture.prescale(0.7);
  world_from_texture.prerotate(Eigen::AngleAxisd(30 * M_PI / 180, Vector3d::UnitZ()));
  return world_from_texture.inverse() * x;
}

const char* const kNoiseTransform =
    R"("transform": {"scale": 0.7, "rotate": {"axis": [0, 0, 1], "deg": 30}})";

}  // namespace

TEST(TextureProgram, AMixByFbmNoiseMatchesItsAnalyticValueEverywhere) {
  const std::string textures = std::string(R"("textures": {
      "cloud": {"type": "fbm", "octaves": 5, "roughness": 0.6, )") +
                               kNoiseTransform + R"(},
      "sky": {"type": "mix", "tex1": 0.9, "tex2": {"rgb": [0.1, 0.3, 0.8]},
              "amount": {"texture": "cloud"}}})";
  const std::string floor =
      R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "sky"}})";
  const std::string scene = floor_scene("program_fbm", floor, kSky, textures);
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    const Vector3d p = noise_space(x);
    const double a = perlin_fbm(float(p.x()), float(p.y()), float(p.z()), 0.6f, 5);
    const double v = (1 - a) * 0.9 + a * rgb_bin({0.1, 0.3, 0.8}, sc, i);
    return 0.8 * std::clamp(v, 0.0, 1.0) * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "photon", radiance, 16, 1 << 14, 1);
  expect_floor(scene, "forward", radiance, 0, 1 << 18, 2);
}

TEST(TextureProgram, ACheckerboardOfDotsAndABilerpMatchesItsAnalyticValue) {
  const std::string textures = R"("textures": {
      "dots": {"type": "dots", "inside": {"rgb": [0.8, 0.2, 0.1]}, "outside": 0.6,
               "uscale": 10, "vscale": 10},
      "ramp": {"type": "bilerp", "v00": 0.1, "v01": 0.9, "v10": 0.5, "v11": 0.3},
      "both": {"type": "checkerboard", "even": {"texture": "dots"},
               "odd": {"texture": "ramp"}, "uscale": 3, "vscale": 3}})";
  const std::string floor =
      R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "both"}})";
  const std::string scene = floor_scene("program_checker", floor, kSky, textures);
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    const Eigen::Vector2d uv = floor_uv(x);
    const bool odd = (int(std::floor(3 * uv.x())) + int(std::floor(3 * uv.y()))) % 2 != 0;
    double v;
    if (odd) {
      const double s = uv.x(), t = uv.y();
      v = (1 - s) * (1 - t) * 0.1 + (1 - s) * t * 0.9 + s * (1 - t) * 0.5 + s * t * 0.3;
    } else {
      const bool inside = polka_dot(float(10 * uv.x()), float(10 * uv.y())) > 0;
      v = inside ? rgb_bin({0.8, 0.2, 0.1}, sc, i) : 0.6;
    }
    return 0.8 * v * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
}

TEST(TextureProgram, AWindyScaleAndMarbleMatchTheirAnalyticValues) {
  const std::string textures = std::string(R"("textures": {
      "wind": {"type": "windy", )") +
                               kNoiseTransform + R"(},
      "gust": {"type": "scale", "tex": {"rgb": [0.9, 0.7, 0.4]}, "scale": {"texture": "wind"}},
      "stone": {"type": "marble", "scale": 1.5, "variation": 0.4, "octaves": 4, )" +
                               kNoiseTransform + R"(},
      "half": {"type": "checkerboard", "even": {"texture": "gust"},
               "odd": {"texture": "stone"}, "uscale": 1, "vscale": 2}})";
  const std::string floor =
      R"({"passive": {"reflectance": 1.0}, "textures": {"reflectance": "half"}})";
  const std::string scene = floor_scene("program_windy", floor, kSky, textures);
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    const Eigen::Vector2d uv = floor_uv(x);
    const Vector3d p = noise_space(x);
    const float px = float(p.x()), py = float(p.y()), pz = float(p.z());
    double v;
    if ((int(std::floor(uv.x())) + int(std::floor(2 * uv.y()))) % 2 == 0) {
      const double wind = std::abs(perlin_fbm(0.1f * px, 0.1f * py, 0.1f * pz, 0.5f, 3)) *
                          perlin_fbm(px, py, pz, 0.5f, 6);
      v = std::clamp(wind * rgb_bin({0.9, 0.7, 0.4}, sc, i), 0.0, 1.0);
    } else {
      const float s = 1.5f;
      const double t =
          0.5 + 0.5 * std::sin(s * py + 0.4 * perlin_fbm(s * px, s * py, s * pz, 0.5f, 4));
      v = rgb_bin(marble_rgb(t), sc, i);
    }
    return v * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
}

TEST(TextureProgram, NoiseIsZeroOnTheLatticeAndBounded) {
  for (int k = -3; k <= 3; ++k) EXPECT_EQ(perlin_noise(float(k), float(2 * k), float(-k)), 0.0f);
  float lo = 1, hi = -1;
  for (int k = 0; k < 4000; ++k) {
    const float v = perlin_noise(0.37f * k, 0.11f * k - 3, 0.05f * k + 0.5f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, -1.0f);
  EXPECT_LE(hi, 1.0f);
  EXPECT_LT(lo, -0.3f);  // it varies: both signs, well away from 0
  EXPECT_GT(hi, 0.3f);
}

TEST(TextureProgram, BadTexturesAreOneLine) {
  const std::string floor_of = R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": )";
  auto fails = [&](const std::string& name, const std::string& textures, const std::string& use,
                   const std::string& expected) {
    const std::string floor = floor_of + "\"" + use + "\"}}";
    const std::string path = floor_scene(name, floor, kSky, "\"textures\": {" + textures + "}");
    const std::string error = error_of([&] {
      Scene s = load_scene(path);
      KernelSceneData data(s);
    });
    EXPECT_NE(error.find(expected), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  };
  fails("prog_unknown", R"("m": {"type": "mix", "tex1": {"texture": "nowhere"}})", "m",
        "/textures/m/tex1: no texture named \"nowhere\"");
  fails("prog_cycle",
        R"("a": {"type": "mix", "tex1": {"texture": "b"}},
           "b": {"type": "scale", "tex": {"texture": "a"}})",
        "a", "names itself in turn");
  fails("prog_marble_amount",
        R"("s": {"type": "marble"}, "m": {"type": "mix", "amount": {"texture": "s"}})", "m",
        "/textures/s: a marble texture is a colour, and a number is needed here");
  fails("prog_rgb_amount", R"("m": {"type": "mix", "amount": {"rgb": [0.2, 0.3, 0.4]}})", "m",
        "/textures/m/amount: a spectrum where a texture of numbers needs a number");
  fails("prog_unknown_key", R"("m": {"type": "mix", "amont": 0.3})", "m",
        "/textures/m/amont: unknown key");
  fails("prog_3d_mapping", R"("f": {"type": "fbm", "mapping": "planar"})", "f",
        "a 3D texture maps the point itself");
  fails("prog_bilerp_texture",
        R"("f": {"type": "fbm"}, "b": {"type": "bilerp", "v00": {"texture": "f"}})", "b",
        "a bilerp's corners are values");
}

TEST(TextureProgram, AProgramBeyondItsSlotsIsRefusedNamingTheTexture) {
  // Twenty mixes in a chain, each of the one before by fbm noise: more steps than the kernels'
  // private slots.
  std::string textures = R"("t0": {"type": "fbm"})";
  for (int k = 1; k <= 20; ++k) {
    const std::string prev = "\"t" + std::to_string(k - 1) + "\"";
    textures +=
        ", \"t" + std::to_string(k) + "\": {\"type\": \"mix\", \"tex1\": {\"texture\": " + prev +
        "}, \"amount\": {\"texture\": \"n" + std::to_string(k) + "\"}}, \"n" + std::to_string(k) +
        "\": {\"type\": \"fbm\", \"octaves\": " + std::to_string(k) + "}";
  }
  const std::string path = floor_scene(
      "prog_deep", R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "t20"}})", kSky,
      "\"textures\": {" + textures + "}");
  const std::string error = error_of([&] {
    Scene s = load_scene(path);
    KernelSceneData data(s);
  });
  EXPECT_NE(error.find("/textures/t20: the texture \"t20\" needs more than 32 steps"),
            std::string::npos)
      << error;
}
