// The thin dielectric (pbrt-v4's ThinDielectricBxDF; docs/materials.md#thin-dielectric): a sheet
// that reflects R' = R + T²R / (1 − R²) and passes the rest straight through. An emitter seen
// through a tilted sheet against pbrt-v4's formula (on the tests' own Fresnel reference), its
// parsing and import, and a furnace in every integrator: a lossless sheet leaves the passive
// furnace's uniform radiance unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "furnace_scene.h"
#include "material/material.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "scene/pbrt/pbrt_import.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// pbrt-v4's ThinDielectricBxDF reflectance, from the tests' Fresnel reference.
double thin_reflectance(double cos_i, double eta) {
  double r = fresnel_reference(cos_i, {eta, 0.0}), t = 1 - r;
  return r < 1 ? r + t * t * r / (1 - r * r) : r;
}

std::string emitter_csv() {
  return source_path("scenes/data/CIE_D65_300_780.csv");
}

TEST(ThinDielectric, EmitterSeenThroughATiltedSheetTakesOneMinusPbrtsReflectance) {
  // The sheet's normal (sin 60°, 0, cos 60°): the camera's rays meet it at 60° from it.
  const std::string scene = R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 1, "width": 8, "height": 8},
    "materials": {"black": {}, "sheet": {"dielectric": {"eta": 1.5, "thin": true}}},
    "shapes": [
      {"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "black",
       "emission": {"csv": ")" +
                            emitter_csv() + R"(", "scale": 0.01}},
      {"type": "quad", "corner": [-0.5, -2, 2.366], "u": [0, 4, 0], "v": [1, 0, -1.732], "material": "sheet"}]})";
  const std::string path = write_file("thin_sheet.json", scene);
  RenderSettings s;
  s.integrator = "backward";
  s.grid = GridRequest{380, 780, 20};
  s.integrator_settings.spp = 256;
  s.passes = 12;
  RenderResult r = render_scene(path, s);
  const double t = 1 - thin_reflectance(0.5, 1.5);
  // Not a single interface's 1 − R, nor two without their round trips, (1 − R)².
  const double single = 1 - fresnel_reference(0.5, {1.5, 0.0});
  ASSERT_GT(std::abs(t - single * single), 0.005);
  std::vector<double> truth = r.scene.emitters.at(0).per_bin;
  for (double& v : truth) v *= t;
  expect_bins_match(r, truth, 0.004, "thin sheet", true);
}

TEST(ThinDielectric, ParsedAndImportedAsPbrtV4) {
  JsonNode node = JsonNode::from_json(
      nlohmann::json::parse(R"({"dielectric": {"eta": 1.33, "thin": true}})"), "m.json");
  Material m = discretize_material(parse_material(node, "m"), WavelengthGrid{});
  EXPECT_TRUE(m.thin);
  EXPECT_DOUBLE_EQ(m.eta, 1.33);
  const std::string rough = error_of([] {
    JsonNode n = JsonNode::from_json(
        nlohmann::json::parse(R"({"dielectric": {"thin": true, "roughness": 0.2}})"), "r.json");
    parse_material(n, "r");
  });
  EXPECT_NE(rough.find("a thin dielectric is smooth"), std::string::npos) << rough;
  const nlohmann::json s = import_pbrt_scene(
      write_file("thin.pbrt",
                 "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                 "MakeNamedMaterial \"pane\" \"string type\" \"thindielectric\"\n"
                 "NamedMaterial \"pane\"\nShape \"sphere\"\n"),
      {});
  // pbrt-v4's ThinDielectricMaterial: eta 1.5 by default.
  EXPECT_EQ(s.at("materials").at("pane"),
            nlohmann::json::parse(R"({"dielectric": {"eta": 1.5, "thin": true}})"));
}

class ThinFurnace : public ::testing::TestWithParam<std::string> {};

// A thin glass sphere leaves the passive furnace's radiance unchanged.
TEST_P(ThinFurnace, LosslessSheetLeavesTheFurnaceUniform) {
  const std::string integrator = GetParam();
  const std::string materials = with_clay(R"("pane": {"dielectric": {"eta": 1.5, "thin": true}})");
  const bool in_view = IntegratorRegistry::find(integrator).traits.sees_camera_mirrors;
  const FurnaceObject pane{"pane", in_view ? 0.35 : 0.3, in_view};
  expect_furnace_render(integrator, furnace_scene(materials, "clay", pane),
                        furnace_radiance(furnace_scene(materials)));
}

INSTANTIATE_TEST_SUITE_P(Registry, ThinFurnace,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

}  // namespace
