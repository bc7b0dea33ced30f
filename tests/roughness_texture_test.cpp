// Roughness given by a scalar texture (pbrt-v4's "texture roughness";
// docs/materials.md#rough-surfaces):
// - parsing: {"texture": NAME} on a dielectric's or conductor's roughness keys, resolved by the
//   scene, refused on a coat and where no texture has the name; the kernels carry the code only
//   where a scene has one;
// - a rough gold floor whose roughness is a checkerboard of 0.04 and 0.36 under a point light
//   renders, in each square, what gold of that constant roughness renders (backward and vcm, within
//   4 standard errors of the difference), and the two constants differ there (the test sees it);
// - in the passive furnace, a lossless metal sphere whose roughness texture is 0 (smooth: a delta
//   mirror) on half its squares and 0.0025 on the others keeps the furnace's radiance (within its
//   GGX's small loss, never above) in every integrator, as the constant 0.0025 one does: each point
//   is smooth or rough alike for the camera's and the light's paths;
// - the pbrt-v4 importer keeps a varying "texture roughness" as the texture's reference.
#include <gtest/gtest.h>

#include <cmath>

#include "analytic_floor.h"
#include "furnace_scene.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "scene/pbrt/pbrt_import.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

const char* const kChecks = R"({"r": {"type": "checkerboard", "even": 0.04, "odd": 0.36,
    "uscale": 4, "vscale": 4}})";

TEST(RoughnessTexture, ParsedResolvedAndRefused) {
  const std::string materials = with_clay(
      R"("a": {"conductor": {"metal": "Au", "roughness": {"texture": "r"}}},
         "b": {"dielectric": {"eta": 1.5, "uroughness": {"texture": "r"}, "vroughness": 0.25,
                              "remap_roughness": false}})");
  const Scene s = load_scene(write_file(
      "rtex.json", furnace_scene(materials, "clay", FurnaceObject{"a", 0.3, true}, kChecks)));
  const Material& a = s.materials.at(s.material_index("a"));
  EXPECT_TRUE(a.rough());
  EXPECT_TRUE(a.roughness.textured());
  EXPECT_FALSE(a.roughness.anisotropic());
  EXPECT_EQ(a.roughness.texture[0], 0);
  EXPECT_EQ(a.roughness.texture[1], 0);
  EXPECT_TRUE(s.roughness_textured());
  EXPECT_TRUE(s.textured());
  EXPECT_TRUE(s.rough());
  // 0.04 and 0.36 are rough everywhere: nothing scatters by a delta lobe.
  EXPECT_FALSE(a.roughness.may_be_smooth);
  EXPECT_FALSE(s.has_delta_surfaces());
  EXPECT_FALSE(s.partly_smooth_conductor());
  const Material& b = s.materials.at(s.material_index("b"));
  EXPECT_EQ(b.roughness.texture[0], 0);
  EXPECT_EQ(b.roughness.texture[1], -1);
  EXPECT_DOUBLE_EQ(b.roughness.alpha_y, 0.25);
  EXPECT_FALSE(b.roughness.remap);
  EXPECT_TRUE(b.roughness.anisotropic());
  // A checkerboard with a 0 square is smooth there: the metal may scatter by a delta lobe.
  const Scene zero = load_scene(
      write_file("rtex_zero.json",
                 furnace_scene(materials, "clay", FurnaceObject{"a", 0.3, true},
                               R"({"r": {"type": "checkerboard", "even": 0, "odd": 0.3}})")));
  EXPECT_TRUE(zero.materials.at(zero.material_index("a")).roughness.may_be_smooth);
  EXPECT_TRUE(zero.has_delta_surfaces());
  EXPECT_TRUE(zero.partly_smooth_conductor());
  const auto refused = [](const std::string& material, const std::string& textures = kChecks) {
    return error_of([&] {
      load_scene(
          write_file("rtex_bad.json", furnace_scene(with_clay(R"("m": )" + material), "clay",
                                                    FurnaceObject{"m", 0.3, true}, textures)));
    });
  };
  EXPECT_NE(refused(R"({"conductor": {"roughness": {"texture": "nope"}}})")
                .find("/materials/m/conductor/roughness: no texture named \"nope\""),
            std::string::npos);
  EXPECT_NE(refused(R"({"conductor": {"roughness": {"texture": "r"}}})",
                    R"({"r": {"type": "checkerboard", "even": 0.5, "odd": 2}})")
                .find("numbers in [0, 1]"),
            std::string::npos);
  EXPECT_NE(refused(R"({"conductor": {"roughness": {"texture": "r", "scale": 2}}})").find("scale"),
            std::string::npos);
  // A coat takes one roughness, a texture's mean: a texture of textures has none kasha takes.
  EXPECT_NE(refused(R"({"passive": {"reflectance": 0.5}, "coat": {"roughness": {"texture": "r"}}})",
                    R"({"r": {"type": "fbm"}})")
                .find("a coat takes one roughness: its texture must be an image or a checkerboard"),
            std::string::npos);
  EXPECT_NE(refused(R"({"dielectric": {"thin": true, "roughness": {"texture": "r"}}})")
                .find("a thin dielectric is smooth"),
            std::string::npos);
  // The kernels carry the per-point roughness only where a scene has one.
  CommandResult info =
      run_kasha("info " + write_file("rtex_info.json",
                                     furnace_scene(materials, "clay", FurnaceObject{"a", 0.3, true},
                                                   kChecks)));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("-D KASHA_ROUGHNESS_TEXTURES=1"), std::string::npos) << info.out;
  info = run_kasha("info " + write_file("rtex_plain.json",
                                        furnace_scene(materials, "clay", std::nullopt, kChecks)));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("-D KASHA_ROUGHNESS_TEXTURES=0"), std::string::npos) << info.out;
}

// The floor's pixels wholly inside an even or an odd square of a 4 × 4 checkerboard.
std::pair<std::vector<size_t>, std::vector<size_t>> square_pixels(const Scene& scene) {
  const KCamera cam = scene.camera.to_kernel();
  std::vector<size_t> even, odd;
  for (int py = 0; py < kFloorSize; ++py)
    for (int px = 0; px < kFloorSize; ++px) {
      int parity = -1;
      for (int a = 0; a <= 4 && parity != -2; ++a)
        for (int b = 0; b <= 4; ++b) {
          const Eigen::Vector3d x = floor_point(cam, px + a / 4.0, py + b / 4.0);
          const double u = (x.x() + 2) / 4, v = (x.y() + 2) / 4;
          const int p = (int(std::floor(4 * u)) + int(std::floor(4 * v))) & 1;
          if (parity == -1) parity = p;
          if (p != parity) {
            parity = -2;
            break;
          }
        }
      if (parity == 0) even.push_back(py * kFloorSize + px);
      if (parity == 1) odd.push_back(py * kFloorSize + px);
    }
  return {even, odd};
}

TEST(RoughnessTexture, EachSquareRendersAsItsConstantRoughness) {
  const std::string lamp = R"({"type": "point", "position": [0.3, 0.2, 1.2], "intensity": 2})";
  const std::string textures = std::string(R"("textures": )") + kChecks;
  auto gold = [](const std::string& roughness) {
    return R"({"conductor": {"metal": "Au", "roughness": )" + roughness + "}}";
  };
  for (const char* integrator : {"backward", "vcm"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.passes = 2;
    s.spectral = false;
    s.integrator_settings.spp = 16;
    s.integrator_settings.photons = 1 << 12;
    const RenderResult textured =
        render_scene(floor_scene("rtex_floor", gold(R"({"texture": "r"})"), lamp, textures), s);
    const RenderResult smoother = render_scene(floor_scene("rtex_004", gold("0.04"), lamp), s);
    const RenderResult rougher = render_scene(floor_scene("rtex_036", gold("0.36"), lamp), s);
    const auto [even, odd] = square_pixels(textured.scene);
    ASSERT_GT(even.size(), 50u);
    ASSERT_GT(odd.size(), 50u);
    double apart = 0;  // the two constants' largest relative difference over the squares
    for (auto [pixels, same, other, label] : {std::tuple{even, &smoother, &rougher, "even (0.04)"},
                                              std::tuple{odd, &rougher, &smoother, "odd (0.36)"}}) {
      const BinStats d = difference_statistics(textured.image, same->image, false, pixels);
      const BinStats t = pixel_statistics(same->image, false, pixels);
      const BinStats o = pixel_statistics(other->image, false, pixels);
      for (int k = 0; k < 3; ++k) {
        std::printf(
            "  %s %s row %d: textured − constant %+.3g ± %.2g; the other constant %+.1f %%\n",
            integrator, label, k, d.mean[k], d.standard_error[k],
            100 * (o.mean[k] / t.mean[k] - 1));
        EXPECT_LE(std::abs(d.mean[k]), 4 * d.standard_error[k] + 1e-6 * t.mean[k])
            << integrator << " " << label << " row " << k;
        apart = std::max(apart, std::abs(o.mean[k] / t.mean[k] - 1));
      }
    }
    EXPECT_GT(apart, 0.1) << integrator << ": the two roughnesses must render apart";
  }
}

class RoughnessTextureFurnace : public ::testing::TestWithParam<std::string> {};

// A lossless metal (k large: it reflects all) smooth on half its squares and rough (0.0025, alpha
// 0.05) on the others, in the furnace: GGX's single scattering keeps all but a few tenths of a
// percent where it is rough, so the field stays within 2 % (4 % for a consistent integrator) of the
// furnace's and never above it (within 4 standard errors), as with the constant roughness.
TEST_P(RoughnessTextureFurnace, ALosslessMetalOfTexturedRoughnessKeepsTheFurnace) {
  const std::string integrator = GetParam();
  const IntegratorInfo& info = IntegratorRegistry::find(integrator);
  const std::string materials = with_clay(
      R"("textured": {"conductor": {"eta": 0.001, "k": 1000, "roughness": {"texture": "half"}}},
         "constant": {"conductor": {"eta": 0.001, "k": 1000, "roughness": 0.0025}})");
  const std::string textures =
      R"({"half": {"type": "checkerboard", "even": 0, "odd": 0.0025, "uscale": 8, "vscale": 4}})";
  // The smooth squares are mirrors, which light tracing does not see from the camera.
  const bool in_view = info.traits.sees_camera_mirrors;
  const std::vector<double> truth =
      furnace_radiance(furnace_scene(materials, "clay", std::nullopt, textures));
  RenderSettings s;
  s.integrator = integrator;
  s.grid = kFurnaceGrid;
  s.integrator_settings.spp = 8;
  s.integrator_settings.photons = integrator == "ppm" ? 1 << 15 : 1 << 13;
  s.passes = info.traits.unbiased ? 12 : 16;
  const double tolerance = info.traits.unbiased ? 0.02 : 0.04;
  for (const char* sphere : {"textured", "constant"}) {
    const RenderResult r = render_scene(
        write_file(
            std::string("rtex_furnace_") + sphere + ".json",
            furnace_scene(materials, "clay", FurnaceObject{sphere, 0.35, in_view}, textures)),
        s);
    const BinStats st = pixel_statistics(r.image, true);
    double worst = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      worst = std::max(worst, std::abs(st.mean[i] / truth[i] - 1));
      EXPECT_LT(std::abs(st.mean[i] - truth[i]), tolerance * truth[i]) << sphere << " bin " << i;
      EXPECT_LT(st.mean[i], truth[i] + 4 * st.standard_error[i]) << sphere << " bin " << i;
    }
    std::printf("  %s, %s: worst bin off the furnace by %.4f\n", integrator.c_str(), sphere, worst);
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, RoughnessTextureFurnace,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

const char* kHead =
    "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";
const char* kQuad =
    "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
    "\"integer indices\" [0 1 2  0 2 3]\n";

TEST(RoughnessTexture, PbrtKeepsAVaryingTextureAsItsReference) {
  const std::string body =
      R"(Texture "checks" "float" "checkerboard" "float tex1" 0.01 "float tex2" 0.2
Texture "half" "float" "scale" "texture tex" "checks" "float scale" 0.5
MakeNamedMaterial "c" "string type" "conductor" "texture roughness" "checks"
MakeNamedMaterial "d" "string type" "dielectric" "texture uroughness" "half" "float vroughness" 0.1
    "bool remaproughness" false
NamedMaterial "c"
)";
  const std::string path = write_file("rtex.pbrt", std::string(kHead) + body + kQuad);
  const nlohmann::json s = import_pbrt_scene(path, {});
  const nlohmann::json& c = s.at("materials").at("c").at("conductor");
  const std::string checks = c.at("roughness").at("texture");
  ASSERT_TRUE(s.at("textures").contains(checks)) << s.dump();
  EXPECT_EQ(s.at("textures").at(checks).at("odd"), 0.2);
  const nlohmann::json& d = s.at("materials").at("d").at("dielectric");
  const std::string half = d.at("uroughness").at("texture");
  EXPECT_EQ(s.at("textures").at(half).at("type"), "scale");
  EXPECT_EQ(d.at("vroughness"), 0.1);
  EXPECT_EQ(d.at("remap_roughness"), false);
  const Scene loaded = load_scene(path);
  EXPECT_TRUE(loaded.roughness_textured());
  // A coat takes one roughness: a texture there is read as its mean (the checkerboard's 1 and
  // 0: 0.5, remapped to alpha √0.5), with a warning naming its line.
  const std::string coat_file =
      write_file("rtex_coat.pbrt", std::string(kHead) + R"(Texture "checks" "float" "checkerboard"
Material "coateddiffuse" "texture roughness" "checks"
)" + kQuad);
  const Scene coated = load_scene(coat_file);
  bool found = false;
  for (const Material& m : coated.materials)
    if (m.coat) {
      EXPECT_NEAR(m.coat->alpha, std::sqrt(0.5), 1e-12);
      found = true;
    }
  EXPECT_TRUE(found);
  CommandResult r = run_kasha("info " + coat_file);
  EXPECT_NE(r.err.find("rtex_coat.pbrt:6: a coat takes one roughness in kasha: its texture is read "
                       "as its mean, 0.5"),
            std::string::npos)
      << r.err;
}

}  // namespace
