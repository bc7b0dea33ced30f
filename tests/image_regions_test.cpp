// Measuring an image over the shapes of its scene: which pixels lie well inside each shape, their
// mean XYZ and standard error, relative to a white reference; `kasha regions`, `kasha preview`
// and `kasha delta-e` on the command line.
#include "study/image_regions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "colorimetry/cie_lab.h"
#include "image/exr_io.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// Two quads side by side filling an 8 × 8 view exactly: x ∈ [0, 2] ("left", on the image's left
// since the camera looks along +z with up +y) and x ∈ [−2, 0] ("right").
std::string two_quads() {
  return write_file("two.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 90, "width": 8, "height": 8},
    "materials": {"left": {"passive": {"reflectance": 0.2}}, "right": {"passive": {"reflectance": 0.5}}},
    "shapes": [{"type": "quad", "corner": [0, -2, 0], "u": [2, 0, 0], "v": [0, 4, 0], "material": "left"},
               {"type": "quad", "corner": [-2, -2, 0], "u": [2, 0, 0], "v": [0, 4, 0], "material": "right"}]})");
}

Image constant_halves(const Vec3d& left, const Vec3d& right) {
  Image img;
  img.width = img.height = 8;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) img.xyz.push_back(static_cast<float>(x < 4 ? left[c] : right[c]));
  return img;
}

}  // namespace

TEST(ImageRegions, PixelsWellInsideEachShape) {
  Scene scene = load_scene(two_quads());
  std::vector<ShapeRegion> all = shape_regions(scene, scene.camera);
  ASSERT_EQ(all.size(), 2u);
  for (const ShapeRegion& r : all) {
    EXPECT_EQ(r.pixels.size(), 32u);
    for (size_t p : r.pixels) EXPECT_EQ(p % 8 < 4, r.shape == 0) << p;  // shape 0 on the left
  }
  // A margin of one pixel drops the column beside the other quad and the image's border (beyond
  // it the rays miss): 2 columns × 6 rows.
  std::vector<ShapeRegion> inside = shape_regions(scene, scene.camera, 1.0);
  ASSERT_EQ(inside.size(), 2u);
  for (const ShapeRegion& r : inside) {
    EXPECT_EQ(r.pixels.size(), 12u);
    for (size_t p : r.pixels) {
      const size_t x = p % 8, y = p / 8;
      EXPECT_TRUE(y >= 1 && y <= 6) << p;
      EXPECT_TRUE(r.shape == 0 ? (x == 1 || x == 2) : (x == 5 || x == 6)) << p;
    }
  }
  Image img = constant_halves({1, 2, 3}, {4, 5, 6});
  img.xyz[3 * 9 + 1] = 4;  // one pixel of the left region (x 1, y 1) brighter in Y
  RegionXyz m = region_xyz(img, inside[0].pixels);
  EXPECT_DOUBLE_EQ(m.mean[0], 1);
  EXPECT_DOUBLE_EQ(m.mean[1], 2 + 2.0 / 12);
  EXPECT_DOUBLE_EQ(m.standard_error[0], 0);
  // Sample standard deviation of eleven 2s and one 4, over √12.
  EXPECT_NEAR(m.standard_error[1],
              std::sqrt((11 * std::pow(2.0 / 12, 2) + std::pow(2 - 2.0 / 12, 2)) / 11 / 12), 1e-12);
}

TEST(ImageRegions, CommandMeasuresRelativeToAWhiteReference) {
  const std::string scene = two_quads(), d = scratch_dir().string();
  write_exr(d + "/image.exr", constant_halves({20, 30, 40}, {50, 50, 50}));
  const Vec3d white{95.047 * 2, 200, 108.883 * 2};
  write_exr(d + "/white.exr", constant_halves(white, white));
  auto r = run_kasha("regions " + scene + " " + d + "/image.exr --white " + d +
                     "/white.exr --margin 1 --json " + d + "/regions.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(d + "/regions.json"));
  ASSERT_EQ(j["regions"].size(), 2u);
  const nlohmann::json& left = j["regions"][0];
  EXPECT_EQ(left["material"], "left");
  EXPECT_EQ(left["pixels"], 12);
  const Vec3d relative{10, 15, 20};
  Vec3d lab = xyz_to_lab(relative, {95.047, 100, 108.883});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(left["XYZ_relative"][k].get<double>(), relative[k], 1e-4);
    EXPECT_NEAR(left["Lab"][k].get<double>(), lab[k], 1e-4);
  }
  // An image from another camera is refused.
  Image small = constant_halves({1, 1, 1}, {1, 1, 1});
  small.width = 4;
  small.xyz.resize(3 * 4 * 8);
  write_exr(d + "/small.exr", small);
  r = run_kasha("regions " + scene + " " + d + "/small.exr");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("small.exr: 4x8 pixels, but the camera of"), std::string::npos) << r.err;
}

TEST(ImageRegions, PreviewAndDeltaECommands) {
  const std::string d = scratch_dir().string();
  write_exr(d + "/image.exr", constant_halves({20, 30, 40}, {50, 50, 50}));
  auto r = run_kasha("preview " + d + "/image.exr -o " + d + "/image.png --scale 0.01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(d + "/image.png"), 50u);
  r = run_kasha("delta-e 50,2.6772,-79.7751 50,0,-82.7485");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "2.0425\n");  // Sharma, Wu and Dalal (2005), pair 1
  r = run_kasha("delta-e 50,2.6772 50,0,-82.7485");
  EXPECT_EQ(r.exit_code, 2);  // a usage error: the command line is wrong
  EXPECT_EQ(r.err,
            "kasha: error: lab1: \"50,2.6772\" is not L*,a*,b* (three numbers separated by "
            "commas)\n");
  // At the ends of the documented range the difference is still a number.
  r = run_kasha("delta-e 0,-10000,-10000 10000,10000,10000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
}

namespace {

// One line on stderr starting `kasha: error: ` + `where`, exit 1, nothing on stdout.
void expect_input_error(const std::string& args, const std::string& where) {
  SCOPED_TRACE("kasha " + args);
  auto r = run_kasha(args);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("kasha: error: " + where, 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.out, "");
}

}  // namespace

TEST(ImageRegions, EveryCommandThatReadsAnImageRefusesNonFinitePixels) {
  const std::string scene = two_quads(), d = scratch_dir().string();
  const Image good = constant_halves({20, 30, 40}, {50, 50, 50});
  Image nan = good, inf = good;
  nan.xyz[3 * (2 * 8 + 1) + 1] = std::nanf("");  // pixel (1, 2), inside the left region
  inf.xyz[3 * (6 * 8 + 5) + 2] = std::numeric_limits<float>::infinity();  // (5, 6), right
  write_exr(d + "/good.exr", good);
  write_exr(d + "/nan.exr", nan);
  write_exr(d + "/inf.exr", inf);
  const std::string bad_nan = d + "/nan.exr: pixel (1, 2) channel XYZ.Y is nan";
  const std::string bad_inf = d + "/inf.exr: pixel (5, 6) channel XYZ.Z is inf";
  expect_input_error("regions " + scene + " " + d + "/nan.exr", bad_nan);
  expect_input_error(
      "regions " + scene + " " + d + "/good.exr --white " + d + "/inf.exr --json " + d + "/r.json",
      bad_inf);
  expect_input_error("compare " + d + "/nan.exr " + d + "/good.exr", bad_nan);
  expect_input_error("compare " + d + "/good.exr " + d + "/inf.exr", bad_inf);
  expect_input_error("preview " + d + "/nan.exr -o " + d + "/p.png", bad_nan);
  expect_input_error(
      "render " + scene + " --passes 1 -o " + d + "/o.exr --reference " + d + "/inf.exr", bad_inf);
  for (const char* written : {"r.json", "p.png", "o.exr"})
    EXPECT_FALSE(std::filesystem::exists(d + "/" + written)) << written;
}

// A white that is dark in a region gives no XYZ relative to it there: that region is left out and
// the table says so; when the white is dark in every region nothing is left, and that is an error.
TEST(ImageRegions, AWhiteDarkInARegionIsSaidAndDarkEverywhereIsRefused) {
  const std::string scene = two_quads(), d = scratch_dir().string();
  write_exr(d + "/image.exr", constant_halves({20, 30, 40}, {50, 50, 50}));
  write_exr(d + "/black.exr", constant_halves({0, 0, 0}, {0, 0, 0}));
  expect_input_error("regions " + scene + " " + d + "/image.exr --white " + d +
                         "/black.exr --json " + d + "/r.json",
                     "--white " + d + "/black.exr: the white is dark");
  EXPECT_FALSE(std::filesystem::exists(d + "/r.json"));

  // Dark on the right only (Z = 0 is dark too: CIELAB divides by it).
  write_exr(d + "/half.exr", constant_halves({190, 200, 218}, {190, 200, 0}));
  auto r = run_kasha("regions " + scene + " " + d + "/image.exr --white " + d +
                     "/half.exr --json " + d + "/r.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("left out: shape 1 (the white is dark there"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(d + "/r.json"));
  ASSERT_EQ(j["regions"].size(), 1u);
  EXPECT_EQ(j["regions"][0]["shape"], 0);
  EXPECT_EQ(j["skipped_shapes"], nlohmann::json::array({1}));

  // No pixel has one shape all round it at this margin: no region at all.
  expect_input_error("regions " + scene + " " + d + "/image.exr --margin 5", scene + ": no pixel");
}

// Every pixel of a view filled by a lamp sees an emitter: without them nothing is left, which is
// said in words rather than as an RMSE of 0; a scene that does not fit is refused before anything
// is printed.
TEST(ImageRegions, CompareSaysWhenNoPixelIsLeftAndChecksTheSceneFirst) {
  const std::string d = scratch_dir().string();
  const std::string lamp = write_file("lamp.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 90, "width": 8, "height": 8},
    "materials": {"grey": {"passive": {"reflectance": 0.5}}},
    "shapes": [{"type": "quad", "corner": [-4, -4, 0], "u": [0, 8, 0], "v": [8, 0, 0],
                "material": "grey", "emission": {"blackbody_K": 5000}}]})");
  write_exr(d + "/a.exr", constant_halves({1, 1, 1}, {1, 1, 1}));
  write_exr(d + "/b.exr", constant_halves({1, 1, 1}, {2, 2, 2}));
  auto r = run_kasha("compare " + d + "/a.exr " + d + "/b.exr --scene " + lamp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| all 64 pixels see an emitter: none left without them\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("rmse 0 "), std::string::npos) << r.out;

  Image small = constant_halves({1, 1, 1}, {1, 1, 1});
  small.width = 4;
  small.xyz.resize(3 * 4 * 8);
  write_exr(d + "/small.exr", small);
  expect_input_error("compare " + d + "/small.exr " + d + "/small.exr --scene " + lamp,
                     "--scene " + lamp + ": its camera is 8x8");
  expect_input_error("compare " + d + "/a.exr " + d + "/a.exr --scene " + d + "/none.json",
                     d + "/none.json: ");
}

TEST(ImageRegions, NamesAreEscapedInJsonAndOnTheTerminal) {
  // A scene or image name that is not UTF-8 used to fail in nlohmann (type_error.316) after the
  // table was printed; a material name holding terminal controls reached stdout raw.
  std::string text = R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 90, "width": 8, "height": 8},
    "materials": {"\u001b[2Jleft": {"passive": {"reflectance": 0.2}}},
    "shapes": [{"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "\u001b[2Jleft"}]})";
  const std::string scene = write_file("s\xff.json", text), d = scratch_dir().string();
  write_exr(d + "/i\xfe.exr", constant_halves({20, 30, 40}, {20, 30, 40}));
  auto r = run_kasha("regions '" + scene + "' '" + d + "/i\xfe.exr' --json " + d + "/r.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\x1B[2Jleft"), std::string::npos) << r.out;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(d + "/r.json"));
  EXPECT_NE(j["scene"].get<std::string>().find("s\\xFF.json"), std::string::npos);
  EXPECT_NE(j["image"].get<std::string>().find("i\\xFE.exr"), std::string::npos);
  EXPECT_EQ(j["regions"][0]["material"], "\x1b[2Jleft");  // valid UTF-8: JSON keeps it as it is
}
