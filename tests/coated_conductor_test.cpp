// The coated conductor (pbrt-v4's coatedconductor with both interfaces smooth;
// docs/materials.md#coated-conductors): a clear coat over a smooth metal reflects
// R = F + (1 − F)² Fc A / (1 − F Fc A) into the mirror direction. An emitter seen in a tilted
// coated-gold sheet against that formula (on the tests' own Fresnel reference), a lossless coated
// metal in the passive furnace of every integrator, and its parsing and import.
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

// pbrt-v4's layered walk for a smooth coat over a smooth conductor, summed: every bounce stays on
// the mirror direction. eta: the coat's index; n + ik the metal's, both over the outside's.
double layered_reflectance(double cos_i, double eta, double n, double k, double thickness) {
  const double F = fresnel_reference(cos_i, {eta, 0.0});
  const double cos_t = std::sqrt(1 - (1 - cos_i * cos_i) / (eta * eta));
  const double fc = fresnel_reference(cos_t, {n / eta, k / eta}) * std::exp(-2 * thickness / cos_t);
  double r = F, term = (1 - F) * fc * (1 - F);
  // The walk's bounces one by one, not the closed form the kernels use.
  for (int bounce = 0; bounce < 200; ++bounce, term *= F * fc) r += term;
  return r;
}

std::string emitter_csv() {
  return source_path("scenes/data/CIE_D65_300_780.csv");
}

TEST(CoatedConductor, EmitterSeenInATiltedCoatedGoldSheetTakesTheLayeredReflectance) {
  // The sheet's normal (sin 60°, 0, cos 60°): the camera's rays meet it at 60° from it and leave
  // towards +x, where the emitter faces them.
  const std::string scene = R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 1, "width": 8, "height": 8},
    "materials": {"black": {},
      "sheet": {"conductor": {"metal": "Au"}, "coat": {"eta": 1.5, "thickness": 0.1}}},
    "shapes": [
      {"type": "quad", "corner": [3, -4, -4], "u": [0, 0, 8], "v": [0, 8, 0], "material": "black",
       "emission": {"csv": ")" +
                            emitter_csv() + R"(", "scale": 0.01}},
      {"type": "quad", "corner": [0.25, -0.5, -0.433], "u": [0, 1, 0], "v": [-0.5, 0, 0.866],
       "material": "sheet"}]})";
  const std::string path = write_file("coated_gold_sheet.json", scene);
  for (const char* integrator : {"backward", "photon", "vcm"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.grid = GridRequest{380, 780, 20};
    s.integrator_settings.spp = 16;
    s.integrator_settings.photons = 1 << 12;
    s.passes = 2;
    RenderResult r = render_scene(path, s);
    const Material& gold = r.scene.materials[r.scene.material_index("sheet")];
    ASSERT_EQ(gold.kind, MaterialKind::conductor);
    std::vector<double> truth = r.scene.emitters.at(0).per_bin;
    double apart = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      const double R = layered_reflectance(0.5, 1.5, gold.eta_c[i], gold.k_c[i], 0.1);
      // Bare gold, or the coat's reflection alone, would be far off.
      apart = std::max(apart, std::abs(R - fresnel_reference(0.5, {gold.eta_c[i], gold.k_c[i]})));
      truth[i] *= R;
    }
    ASSERT_GT(apart, 0.05);
    expect_bins_match(r, truth, 0.004, integrator, true);
  }
}

class CoatedConductorFurnace : public ::testing::TestWithParam<std::string> {};

// A lossless coated metal sphere (thickness 0, k large: the metal reflects all, so the coat's
// round trips return all of what enters it) leaves the passive furnace's radiance unchanged.
TEST_P(CoatedConductorFurnace, LosslessCoatedMetalLeavesTheFurnaceUniform) {
  const std::string integrator = GetParam();
  const std::string materials = with_clay(
      R"("lossless": {"conductor": {"eta": 0.001, "k": 1000}, "coat": {"eta": 1.5, "thickness": 0}})");
  const bool in_view = IntegratorRegistry::find(integrator).traits.sees_camera_mirrors;
  expect_furnace_render(integrator,
                        furnace_scene(materials, "clay", FurnaceObject{"lossless", 0.7, in_view}),
                        furnace_radiance(furnace_scene(materials)));
}

INSTANTIATE_TEST_SUITE_P(Registry, CoatedConductorFurnace,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

// The coat's single reflection without the round trips, F + (1 − F)² Fc, is what the furnace
// above would catch: at normal incidence on the lossless metal it is 4 % short of 1.
TEST(CoatedConductor, TheFurnaceSeesTheRoundTrips) {
  const double F = fresnel_reference(1.0, {1.5, 0.0});
  EXPECT_NEAR(layered_reflectance(1.0, 1.5, 0.001, 1000, 0), 1.0, 1e-6);
  EXPECT_LT(F + (1 - F) * (1 - F), 0.97);
}

Material parsed(const std::string& json) {
  JsonNode node = JsonNode::from_json(nlohmann::json::parse(json), "m.json");
  return discretize_material(parse_material(node, "m"), WavelengthGrid{});
}

std::string refusal(const std::string& json) {
  return error_of([&] { parsed(json); });
}

TEST(CoatedConductor, ParsedWithItsCoatRoughOrSmooth) {
  const Material m = parsed(R"({"conductor": {"metal": "Au"}, "coat": {"thickness": 0.2}})");
  EXPECT_EQ(m.kind, MaterialKind::conductor);
  ASSERT_TRUE(m.coat.has_value());
  EXPECT_DOUBLE_EQ(m.coat->eta, 1.5);
  EXPECT_DOUBLE_EQ(m.coat->thickness, 0.2);
  // Either rough is a rough layered metal (layered_metal_test.cpp), whose metal takes a number.
  const Material rough =
      parsed(R"({"conductor": {"metal": "Au", "roughness": 0.1}, "coat": {"roughness": 0.05}})");
  EXPECT_TRUE(rough.rough());
  ASSERT_TRUE(rough.coat.has_value());
  EXPECT_TRUE(rough.coat->rough());
  const std::string e =
      refusal(R"({"conductor": {"metal": "Au", "roughness": {"texture": "t"}}, "coat": {}})");
  EXPECT_NE(e.find("a conductor under a coat takes a roughness number"), std::string::npos) << e;
  EXPECT_NE(e.find("/coat"), std::string::npos) << e;
  const std::string glass = refusal(R"({"dielectric": {"eta": 1.5}, "coat": {}})");
  EXPECT_NE(glass.find("a dielectric takes no coat"), std::string::npos) << glass;
}

const char* kHeader =
    "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";  // body from line 4

nlohmann::json imported(const std::string& material) {
  const std::string file =
      write_file("cc.pbrt", std::string(kHeader) + material + "\nShape \"sphere\"\n");
  return import_pbrt_scene(file, {}).at("materials");
}

std::string import_error(const std::string& material) {
  const std::string e = error_of([&] {
    load_scene(write_file("cc_bad.pbrt", std::string(kHeader) + material + "\nShape \"sphere\"\n"));
  });
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const size_t at = e.find("cc_bad.pbrt");
  return at == std::string::npos ? e : e.substr(at);
}

TEST(CoatedConductor, ImportedWithPbrtV4sParametersAndDefaults) {
  // pbrt-v4's CoatedConductorMaterial::Create: copper, interface.eta 1.5, thickness 0.01.
  const nlohmann::json d =
      imported("MakeNamedMaterial \"d\" \"string type\" \"coatedconductor\"\nNamedMaterial \"d\"");
  EXPECT_EQ(d.at("d"), nlohmann::json::parse(R"({"conductor": {"metal": "Cu"},
      "coat": {"eta": 1.5, "thickness": 0.01, "remap_roughness": true}})"));
  const nlohmann::json m = imported(
      "MakeNamedMaterial \"g\" \"string type\" \"coatedconductor\" \"float interface.eta\" 1.3 "
      "\"float thickness\" 0.2 \"spectrum conductor.eta\" \"metal-Au-eta\" \"spectrum "
      "conductor.k\" \"metal-Au-k\" \"float interface.roughness\" 0 \"float conductor.roughness\" "
      "0 \"integer maxdepth\" 4 \"integer nsamples\" 2 \"float g\" 0.3 \"rgb albedo\" [0 0 0]\n"
      "MakeNamedMaterial \"r\" \"string type\" \"coatedconductor\" \"rgb reflectance\" [0.9 0.5 "
      "0.2]\nNamedMaterial \"g\"");
  EXPECT_EQ(m.at("g").at("conductor"), nlohmann::json::parse(R"({"metal": "Au"})"));
  EXPECT_EQ(m.at("g").at("coat").at("eta"), 1.3);
  EXPECT_EQ(m.at("g").at("coat").at("thickness"), 0.2);
  // pbrt-v4's artist's metal, η 1 and k from the reflectance; the coat divides both by its index
  // in the kernels as pbrt-v4 does.
  EXPECT_EQ(m.at("r").at("conductor").at("eta"), 1.0);
  EXPECT_TRUE(m.at("r").at("conductor").at("k").is_object());
}

TEST(CoatedConductor, ImportRefusalsNameTheirLine) {
  EXPECT_EQ(import_error("Texture \"s\" \"float\" \"checkerboard\" \"float tex1\" 0.1 "
                         "\"float tex2\" 0.2\n"
                         "Material \"coatedconductor\" \"texture conductor.roughness\" \"s\""),
            "cc_bad.pbrt:5: coatedconductor: a textured conductor.roughness is not built in "
            "kasha (the layer under the coat takes one roughness)");
  EXPECT_EQ(import_error("Material \"coatedconductor\" \"rgb albedo\" [0.5 0.5 0.5]"),
            "cc_bad.pbrt:4: coatedconductor: a scattering coat (\"albedo\" > 0) is not built in "
            "kasha");
  EXPECT_EQ(import_error("Material \"coatedconductor\" \"spectrum interface.eta\" \"glass-BK7\""),
            "cc_bad.pbrt:4: coatedconductor: a coat's index must be a number in kasha");
}

}  // namespace
