// Switchable lamps: a scene's named "lamps", the one that is on ("lamp", or --lamp), the shapes
// that emit it ("lamp": true), and the light booth that uses them.
#include <gtest/gtest.h>

#include "scene/scene.h"
#include "spectrum/spectrum_parser.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

std::string lamp_scene(const std::string& lamps, const std::string& shape_extra) {
  return write_file("lamps.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
    "materials": {"grey": {"passive": {"reflectance": 0.5}},
                  "brightener": {"fluorescence": {"excitation": {"gaussian_nm": 350, "fwhm_nm": 40},
                                                  "emission": {"gaussian_nm": 440, "fwhm_nm": 40}}}},
    )" + lamps + R"(
    "shapes": [{"type": "quad", "corner": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0],
                "material": "brightener"},
               {"type": "quad", "corner": [0, 0, 1], "u": [1, 0, 0], "v": [0, 1, 0],
                "material": "grey")" + shape_extra +
                                      "}]}");
}

const char* kTwoLamps =
    R"("lamps": {"warm": {"blackbody_K": 2856}, "uv": {"line_nm": 365, "scale": 2}}, "lamp": "warm",)";

}  // namespace

TEST(SceneLamps, TheChosenLampIsTheEmissionAndSetsTheGrid) {
  const std::string path = lamp_scene(kTwoLamps, R"(, "lamp": true)");
  Scene warm = load_scene(path);
  EXPECT_EQ(warm.lamp, "warm");
  EXPECT_EQ(warm.lamp_names, (std::vector<std::string>{"uv", "warm"}));
  ASSERT_EQ(warm.emitters.size(), 1u);
  EXPECT_EQ(warm.triangles[2].emitter, 0);
  EXPECT_EQ(warm.triangles[0].emitter, -1);
  const int bin = warm.grid.bin_of(555);
  EXPECT_NEAR(warm.emitters[0].per_bin[bin], BlackbodySpectrum(2856).integral(550, 560) / 10,
              1e-12 * warm.emitters[0].per_bin[bin]);
  // The blackbody reaches down past the excitation's tail (above 1e-4 of its peak from 278 nm).
  EXPECT_EQ(warm.grid.min_nm, 270);

  Scene uv = load_scene(path, std::nullopt, "uv");
  EXPECT_EQ(uv.lamp, "uv");
  EXPECT_EQ(uv.grid.min_nm, 360);  // down to the line that excites the brightener
  EXPECT_NEAR(uv.emitters[0].per_bin[0], 0.2, 1e-12);  // 2 W·m⁻²·sr⁻¹ in a 10 nm bin
}

TEST(SceneLamps, MistakesGiveOneClearLine) {
  std::string path = lamp_scene(kTwoLamps, R"(, "lamp": true)");
  EXPECT_NE(error_of([&] {
              load_scene(path, std::nullopt, "D65");
            }).find("--lamp D65: " + path + " has no lamp of that name (uv, warm)"),
            std::string::npos);
  path = lamp_scene("", R"(, "lamp": true)");
  EXPECT_NE(error_of([&] { load_scene(path); }).find("/shapes/1/lamp: \"lamp\" needs the scene's"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_scene(path, std::nullopt, "uv"); }).find("has no \"lamps\""),
            std::string::npos);
  path = lamp_scene(kTwoLamps, R"(, "lamp": true, "emission": 1)");
  EXPECT_NE(error_of([&] { load_scene(path); }).find("\"emission\" or \"lamp\", not both"),
            std::string::npos);
  path = lamp_scene(kTwoLamps, R"(, "emission": 1)");
  EXPECT_NE(error_of([&] { load_scene(path); }).find("/lamps: no shape emits the lamps"),
            std::string::npos);
  path = lamp_scene(R"("lamps": {"warm": 1}, "lamp": "cold",)", R"(, "lamp": true)");
  EXPECT_NE(error_of([&] { load_scene(path); }).find("/lamp: no lamp named \"cold\" (warm)"),
            std::string::npos);
  path = lamp_scene(R"("lamps": {"warm": {"gaussian_nm": 500}}, "lamp": "warm",)",
                    R"(, "lamp": true)");
  EXPECT_NE(error_of([&] { load_scene(path); }).find("/lamps/warm: missing required key"),
            std::string::npos);
}

// The booth's four lamps: each is the emission of the diffuser, and the grid follows it.
TEST(SceneLamps, LightBoothSwitchesItsLamps) {
  const std::string booth = source_path("scenes/light_booth.json");
  const std::map<std::string, std::pair<std::string, double>> lamps = {
      {"D65", {"CIE_D65_300_780.csv", 300}},
      {"TL84", {"RIT_Pointer_Philips_TL-84.csv", 380}},
      {"A", {"CIE_A_300_780.csv", 300}},
      {"UV", {"uv_blacklight_model.csv", 330}}};
  for (const auto& [name, expected] : lamps) {
    Scene s = load_scene(booth, std::nullopt, name);
    EXPECT_EQ(s.lamp, name);
    EXPECT_EQ(s.grid.min_nm, expected.second) << name;
    ASSERT_EQ(s.emitters.size(), 1u);
    std::vector<double> table =
        s.grid.resample(*read_spectrum_csv(source_path("scenes/data/" + expected.first)));
    double sum = 0, table_sum = 0;
    for (int i = 0; i < s.grid.bins; ++i) sum += s.emitters[0].per_bin[i], table_sum += table[i];
    for (int i = 0; i < s.grid.bins; ++i)
      EXPECT_NEAR(s.emitters[0].per_bin[i], sum / table_sum * table[i], 1e-12 * sum)
          << name << " " << s.grid.center(i);
  }
  EXPECT_EQ(load_scene(booth).lamp, "D65");
  auto r = run_kasha("info '" + booth + "' --lamp UV");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("lamp: UV (lamps: A, D65, TL84, UV)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("330–780 nm"), std::string::npos) << r.out;
  r = run_kasha("render '" + booth + "' --lamp D50 --passes 1 -o " +
                (scratch_dir() / "x.exr").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("kasha: error: --lamp D50:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(scratch_dir() / "x.exr"));
}
