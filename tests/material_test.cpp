// Materials: parsing, emission normalization on the grid, energy conservation with clear errors.
#include "material/material.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"

using namespace kasha;
using kasha::test::error_of;

namespace {

MaterialDesc parse(const std::string& json, const std::string& name = "paper") {
  return parse_material(JsonNode::from_json(nlohmann::json::parse(json), "scene.json"), name);
}

WavelengthGrid visible() {
  return WavelengthGrid{380, 10, 40};
}

}  // namespace

TEST(Material, EmissionIsNormalizedOnTheGrid) {
  Material m = discretize_material(parse(R"({
      "passive": {"reflectance": 0.3},
      "fluorescence": {"excitation": {"gaussian_nm": 420, "fwhm_nm": 30, "scale": 0.4},
                       "emission": {"gaussian_nm": 530, "fwhm_nm": 3, "scale": 123}}})"),
                                   visible());
  ASSERT_TRUE(m.fluorescent());
  double sum = 0;
  for (double e : m.e_hat) sum += e;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_NEAR(m.a[4], 0.4 * 0.9, 0.05);  // the bin around 425 nm
  EXPECT_DOUBLE_EQ(m.rho[10], 0.3);
  EXPECT_EQ(m.gloss_reflectance(), 0.0);
}

TEST(Material, OneBinEmissionLine) {
  Material m = discretize_material(
      parse(R"({"fluorescence": {"excitation": 0.5, "emission": {"line_nm": 612}}})"), visible());
  for (int i = 0; i < 40; ++i) EXPECT_DOUBLE_EQ(m.e_hat[i], i == 23 ? 1.0 : 0.0);
}

TEST(Material, EnergyGainNamesTheMaterialAndTheWavelength) {
  std::string msg = error_of([&] {
    discretize_material(
        parse(R"({"passive": {"reflectance": {"nm": [380, 780], "value": [0.5, 0.9]}},
                                  "fluorescence": {"excitation": {"nm": [380, 780], "value": [0.3, 0.3]},
                                                   "emission": 1},
                                  "gloss": {"reflectance": 0.05, "mirror": true}})",
              "ink"),
        visible());
  });
  // g + ρ + a first exceeds 1 where ρ > 0.65: the bin around 535 nm (ρ = 0.655 there).
  EXPECT_NE(msg.find("material 'ink'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("energy gain at 535 nm"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(Material, BadMaterials) {
  auto check = [](const std::string& json, const std::string& expected) {
    std::string msg = error_of([&] { discretize_material(parse(json), visible()); });
    EXPECT_NE(msg.find(expected), std::string::npos) << json << " -> " << msg;
  };
  check(R"({"passive": {"reflectance": 1.2}})", "passive reflectance 1.2");
  check(R"({"fluorescence": {"excitation": 0.2}})",
        "/fluorescence: missing required key \"emission\"");
  check(R"({"fluorescence": {"excitation": 0.2, "emission": {"line_nm": 300}}})",
        "emission is zero over 380");
  check(R"({"gloss": {"reflectance": 0.1, "mirror": true, "cone_deg": 5}})",
        "an ideal mirror has no cone");
  check(R"({"gloss": {"reflectance": 0.1, "profile": {"deg": [0, 20], "value": [1, 0]}}})",
        "outside the cone");
  check(R"({"gloss": {"reflectance": 0.1, "profile": {"deg": [0, 5], "value": [0, 0]}}})",
        "zero everywhere");
  check(R"({"gloss": {"reflectance": 1.5}})", "/gloss/reflectance: value 1.5 is outside [0, 1]");
  check(R"({"passive": {"reflectance": 0.2}, "shine": 1})", "scene.json: /shine: unknown key");
}

TEST(Material, FileWithDiagnosticsIsRead) {
  std::string path = test::write_file("m.json", R"({"kasha_material": 1, "name": "postit",
      "passive": {"reflectance": 0.5}, "diagnostics": {"rank1_residual": 0.02}})");
  MaterialDesc d = load_material_file(path, "");
  EXPECT_EQ(d.name, "postit");
  std::string plain = test::write_file("plain.json", R"({"passive": {"reflectance": 0.5}})");
  EXPECT_NE(error_of([&] { load_material_file(plain, "x"); }).find("not a kasha material file"),
            std::string::npos);
}

TEST(Material, EmptyMaterialIsBlack) {
  Material m = discretize_material(parse("{}"), visible());
  EXPECT_TRUE(m.rho.empty());
  EXPECT_FALSE(m.fluorescent());
  EXPECT_FALSE(m.gloss.has_value());
}
