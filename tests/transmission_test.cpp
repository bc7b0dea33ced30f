// Lambert transmission (pbrt-v4's DiffuseTransmissionBxDF: ρ/π on the side light arrives from,
// τ/π through the surface; docs/materials.md#diffuse-transmission): its parsing and energy check,
// the pbrt importer's defaults and scale, and a furnace in every integrator: a lossless
// transmitter (ρ + τ = 1) inside the passive furnace leaves its uniform radiance Le / (1 − ρ_wall)
// unchanged, which each integrator must find through the object's both sides.
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

Material discretized(const std::string& json) {
  JsonNode node = JsonNode::from_json(nlohmann::json::parse(json), "m.json");
  return discretize_material(parse_material(node, "m"), WavelengthGrid{});
}

TEST(DiffuseTransmission, ScaleMultipliesBothPartsAndEnergyIsChecked) {
  Material m = discretized(R"({"passive": {"reflectance": 0.4},
                               "transmission": {"transmittance": 0.5, "scale": 0.5}})");
  ASSERT_TRUE(m.transmissive());
  for (size_t i = 0; i < m.tau.size(); ++i) {
    EXPECT_NEAR(m.rho[i], 0.2, 1e-12);
    EXPECT_NEAR(m.tau[i], 0.25, 1e-12);
  }
  // Without a passive part the reflectance is 0.
  Material t = discretized(R"({"transmission": {"transmittance": 0.7}})");
  EXPECT_NEAR(t.rho.at(3), 0.0, 1e-12);
  EXPECT_NEAR(t.tau.at(3), 0.7, 1e-12);
  const std::string gain = error_of([] {
    discretized(R"({"passive": {"reflectance": 0.6}, "transmission": {"transmittance": 0.5}})");
  });
  EXPECT_NE(gain.find("+ transmittance 0.5"), std::string::npos) << gain;
  const std::string coat = error_of([] {
    discretized(R"({"passive": {"reflectance": 0.3}, "transmission": {"transmittance": 0.5},
                    "coat": {"eta": 1.5}})");
  });
  EXPECT_NE(coat.find("takes no coat"), std::string::npos) << coat;
}

TEST(DiffuseTransmission, PbrtDefaultsAndScaleAsPbrtV4) {
  const std::string head =
      "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
      "\"integer yresolution\" 8\nWorldBegin\n";
  const std::string quad =
      "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
      "\"integer indices\" [0 1 2  0 2 3]\n";
  const nlohmann::json s = import_pbrt_scene(write_file("dt.pbrt", head + R"(
MakeNamedMaterial "plain" "string type" "diffusetransmission"
MakeNamedMaterial "curtain" "string type" "diffusetransmission" "rgb reflectance" [.45 .45 .45]
    "rgb transmittance" [.45 .45 .45] "float scale" 0.5
NamedMaterial "plain"
)" + quad),
                                             {});
  const nlohmann::json& m = s.at("materials");
  // pbrt-v4's DiffuseTransmissionMaterial: reflectance and transmittance 0.25, scale 1.
  EXPECT_EQ(m.at("plain").at("passive").at("reflectance"), 0.25);
  EXPECT_EQ(m.at("plain").at("transmission"),
            nlohmann::json::parse(R"({"transmittance": 0.25, "scale": 1.0})"));
  EXPECT_EQ(m.at("curtain").at("transmission").at("scale"), 0.5);
  const std::string e = error_of([&] {
    import_pbrt_scene(write_file("dt2.pbrt", head + R"(
Texture "t" "spectrum" "checkerboard" "rgb tex1" [1 1 1] "rgb tex2" [0 0 0]
MakeNamedMaterial "x" "string type" "diffusetransmission" "texture transmittance" "t"
NamedMaterial "x"
)" + quad),
                      {});
  });
  EXPECT_NE(e.find("dt2.pbrt:7: diffusetransmission"), std::string::npos) << e;
}

// A lossless transmitter: ρ rising where τ falls, ρ + τ = 1 in every bin.
const char* kVeil = R"("passive": {"reflectance": {"nm": [380, 780], "value": [0.2, 0.7]}},
    "transmission": {"transmittance": {"nm": [380, 780], "value": [0.8, 0.3]}})";

// The passive furnace (the truth) and the same with the veil in view; `textured`: the veil's
// reflectance texture (a checkerboard of ones) multiplies ρ and τ.
std::string enclosure(bool veil, bool textured = false) {
  const std::string materials =
      with_clay(R"("veil": {)" + std::string(kVeil) +
                (textured ? R"(, "textures": {"reflectance": "ones"}})" : "}"));
  std::optional<FurnaceObject> object;
  if (veil) object = FurnaceObject{"veil", 0.35, true};
  return furnace_scene(
      materials, "clay", object,
      textured ? R"({"ones": {"type": "checkerboard", "even": 1, "odd": 1}})" : "{}");
}

// The textured kernels' path (ρ and τ through the texture) in the two integrators that sample
// the surface from both ends.
TEST(DiffuseTransmission, ATexturedTransmitterKeepsTheFurnaceUniform) {
  for (const char* integrator : {"backward", "vcm"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.grid = GridRequest{380, 780, 40};
    const std::vector<double> truth = furnace_radiance(enclosure(false), *s.grid);
    s.integrator_settings.spp = 8;
    s.integrator_settings.photons = 1 << 13;
    s.passes = 8;
    RenderResult r = render_scene(write_file("veil_textured.json", enclosure(true, true)), s);
    EXPECT_TRUE(r.scene.textured());
    expect_bins_match(r, truth, 0.02, integrator, true);
  }
}

// Lean: KASHA_TRANSMISSION only where a shape's material transmits, so other scenes compile the
// kernels they did before; a thin dielectric's KASHA_THIN alike.
TEST(DiffuseTransmission, KernelsCarryItOnlyWhereASceneUsesIt) {
  CommandResult veil = run_kasha("info " + write_file("veil_info.json", enclosure(true)));
  ASSERT_EQ(veil.exit_code, 0) << veil.err;
  EXPECT_NE(veil.out.find("-D KASHA_TRANSMISSION=1"), std::string::npos) << veil.out;
  EXPECT_NE(veil.out.find("-D KASHA_THIN=0"), std::string::npos) << veil.out;
  CommandResult plain = run_kasha("info " + source_path("scenes/cornell_box.json"));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("-D KASHA_TRANSMISSION=0"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("-D KASHA_THIN=0"), std::string::npos) << plain.out;
}

class TransmissionFurnace : public ::testing::TestWithParam<std::string> {};

TEST_P(TransmissionFurnace, LosslessTransmitterLeavesTheFurnaceUniform) {
  expect_furnace_render(GetParam(), enclosure(true), furnace_radiance(enclosure(false)));
}

INSTANTIATE_TEST_SUITE_P(Registry, TransmissionFurnace,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

}  // namespace
