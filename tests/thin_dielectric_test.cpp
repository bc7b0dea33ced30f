// The thin dielectric (pbrt-v4's ThinDielectricBxDF; docs/materials.md#thin-dielectric): a sheet
// that reflects R' = R + T²R / (1 − R²) and passes the rest straight through. An emitter seen
// through a tilted sheet against pbrt-v4's formula (on the tests' own Fresnel reference), its
// parsing and import, and a furnace in every integrator: a lossless sheet leaves the passive
// furnace's uniform radiance unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
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

// The passive furnace's enclosure with a thin glass sphere: in view where the integrator sees
// delta surfaces from the camera, else behind the camera (light tracing sees none).
std::string enclosure(bool sheet, bool in_view) {
  std::string s = R"({"kasha_scene": 1,
  "camera": {"position": [0.2, -0.1, 0.3], "look_at": [1, 0.3, -0.5], "fov_deg": 60, "width": 16, "height": 16},
  "materials": {
    "clay": {"passive": {"reflectance": {"nm": [380, 450, 550, 650, 780], "value": [0.2, 0.35, 0.6, 0.7, 0.65]}}},
    "pane": {"dielectric": {"eta": 1.5, "thin": true}}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "clay", "inward": true,
     "emission": {"csv": ")" +
                  emitter_csv() + R"(", "scale": 0.01}})";
  if (sheet)
    s +=
        in_view
            ? R"(, {"type": "sphere", "center": [0.8, 0.25, -0.4], "radius": 0.35, "material": "pane"})"
            : R"(, {"type": "sphere", "center": [-0.4, -0.4, 0.9], "radius": 0.3, "material": "pane"})";
  return s + "]}";
}

class ThinFurnace : public ::testing::TestWithParam<std::string> {};

TEST_P(ThinFurnace, LosslessSheetLeavesTheFurnaceUniform) {
  const std::string integrator = GetParam();
  const IntegratorInfo& info = IntegratorRegistry::find(integrator);
  RenderSettings s;
  s.integrator = integrator;
  s.grid = GridRequest{380, 780, 20};
  Furnace f = analyze_furnace(
      load_scene(write_file("thin_enclosure.json", enclosure(false, false)), s.grid));
  ASSERT_TRUE(f.qualifies) << f.why_not;
  const std::string path =
      write_file("thin_" + integrator + ".json", enclosure(true, info.traits.sees_camera_mirrors));
  s.integrator_settings.spp = 8;
  s.integrator_settings.photons = integrator == "ppm" ? 1 << 15 : 1 << 13;
  s.passes = info.traits.unbiased ? 12 : 16;
  RenderResult r = render_scene(path, s);
  BinStats st = pixel_statistics(r.image, true);
  double worst = 0;
  for (size_t i = 0; i < f.radiance.size(); ++i)
    worst = std::max(worst, std::abs(st.mean[i] / f.radiance[i] - 1));
  std::printf("  %s: worst bin of the image mean off the furnace by %.4f\n", integrator.c_str(),
              worst);
  expect_bins_match(r, f.radiance, info.traits.unbiased ? 0.02 : 0.04, integrator,
                    info.traits.unbiased);
}

INSTANTIATE_TEST_SUITE_P(Registry, ThinFurnace,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

}  // namespace
