// Scenes: strict JSON with paths in errors, shapes and their front sides, transforms, camera.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "test_support.h"

using namespace kasha;
using kasha::test::error_of;

namespace {

const char* kMaterials = R"("materials": {"grey": {"passive": {"reflectance": 0.5}}})";
const char* kCamera = R"("camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]})";

std::string scene_with(const std::string& shapes, const std::string& extra = "") {
  return std::string(R"({"kasha_scene": 1, )") + kCamera + ", " + kMaterials + ", " + extra +
         R"("shapes": [)" + shapes + "]}";
}

Scene load(const std::string& text) {
  return load_scene(test::write_file("scene.json", text));
}

Eigen::Vector3d v(const float* p) {
  return {p[0], p[1], p[2]};
}
Eigen::Vector3d normal(const KTriangle& t) {
  return (v(t.v1) - v(t.v0)).cross(v(t.v2) - v(t.v0));
}

// Σ over triangles of (centroid · area-normal)/3: the enclosed volume, positive for outward
// normals.
double signed_volume(const Scene& s) {
  double vol = 0;
  for (const KTriangle& t : s.triangles) vol += v(t.v0).dot(normal(t)) / 6.0;
  return vol;
}

}  // namespace

TEST(Scene, ClosedShapesFaceOutwardUnlessInward) {
  EXPECT_NEAR(signed_volume(load(scene_with(
                  R"({"type": "box", "min": [0,0,0], "max": [1,2,3], "material": "grey"})"))),
              6.0, 1e-5);
  EXPECT_NEAR(
      signed_volume(load(scene_with(
          R"({"type": "box", "min": [0,0,0], "max": [1,2,3], "material": "grey", "inward": true})"))),
      -6.0, 1e-5);
  double sphere = signed_volume(load(
      scene_with(R"({"type": "sphere", "center": [1,2,3], "radius": 2, "material": "grey"})")));
  EXPECT_NEAR(sphere / (4.0 / 3.0 * M_PI * 8), 1.0, 0.01);  // 64 segments: within 1 %
  EXPECT_LT(
      signed_volume(load(scene_with(
          R"({"type": "sphere", "center": [1,2,3], "radius": 2, "material": "grey", "inward": true})"))),
      0);
  // The OBJ torus encloses 2π²Rr² (up to faceting).
  std::string obj = test::source_path("scenes/meshes/torus.obj");
  double torus = signed_volume(
      load(scene_with(R"({"type": "obj", "file": ")" + obj + R"(", "material": "grey"})")));
  EXPECT_NEAR(torus / (2 * M_PI * M_PI * 1.0 * 0.35 * 0.35), 1.0, 0.02);
}

TEST(Scene, QuadFacesUCrossV) {
  Scene s = load(scene_with(
      R"({"type": "quad", "corner": [0,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey",
                                "emission": 2})"));
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const KTriangle& t : s.triangles) {
    EXPECT_GT(normal(t).z(), 0);
    EXPECT_EQ(t.emitter, 0);
  }
  ASSERT_EQ(s.emitters.size(), 1u);
  EXPECT_DOUBLE_EQ(s.emitters[0].per_bin[5], 2.0);
}

TEST(Scene, TransformsScaleRotateTranslate) {
  Scene s = load(scene_with(
      R"({"type": "quad", "corner": [0,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey",
      "transform": {"scale": 2, "rotate": {"axis": [0,0,1], "deg": 90}, "translate": [10, 0, 0]}})"));
  // (1,0,0) → scale (2,0,0) → rotate (0,2,0) → translate (10,2,0).
  EXPECT_NEAR(s.triangles[0].v1[0], 10, 1e-5);
  EXPECT_NEAR(s.triangles[0].v1[1], 2, 1e-5);
  // A mirroring matrix keeps the front side (winding is swapped).
  Scene m = load(scene_with(
      R"({"type": "quad", "corner": [0,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey",
      "transform": {"matrix": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}})"));
  EXPECT_GT(normal(m.triangles[0]).z(), 0);
}

TEST(Scene, CameraConventions) {
  // At the origin looking along +z with up +y, +x is on the left of the image.
  Camera c;
  c.position = {0, 0, 0};
  c.look_at = {0, 0, 1};
  c.up = {0, 1, 0};
  c.width = 200;
  c.height = 100;
  c.fov_deg = 40;
  KCamera k = c.to_kernel();
  EXPECT_LT(k.right[0], 0);  // image right is -x
  EXPECT_GT(k.up[1], 0);
  // The shorter side (height) spans the field of view.
  EXPECT_NEAR(k.up[1], std::tan(20 * M_PI / 180), 1e-6);
  EXPECT_NEAR(-k.right[0], 2 * std::tan(20 * M_PI / 180), 1e-6);
}

TEST(Scene, PathsAreRelativeToTheSceneFile) {
  test::write_file("sub/m.json",
                   R"({"kasha_material": 1, "passive": {"reflectance": {"csv": "r.csv"}}})");
  test::write_file("sub/r.csv", "380,0.1\n780,0.1\n");
  std::string scene = test::write_file(
      "sub/scene.json",
      std::string(R"({"kasha_scene": 1, )") + kCamera +
          R"(, "materials": {"m": {"file": "m.json"}}, "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  Scene s = load_scene(scene);
  EXPECT_NEAR(s.materials[0].rho[3], 0.1, 1e-12);
}

TEST(Scene, UvExcitationExtendsTheGrid) {
  Scene s = load(R"({"kasha_scene": 1, "camera": {"position": [0,0,-5], "look_at": [0,0,0]},
    "materials": {"brightener": {"passive": {"reflectance": 0.8},
                  "fluorescence": {"excitation": {"nm": [300, 350, 400, 420], "value": [0, 0.15, 0.1, 0]},
                                   "emission": {"gaussian_nm": 440, "fwhm_nm": 40}}}},
    "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "brightener", "inward": true,
                "emission": {"line_nm": 365}}]})");
  EXPECT_EQ(s.grid.min_nm, 360);
  EXPECT_TRUE(s.fluorescent());
  EXPECT_FALSE(s.glossy());
}

TEST(Scene, OnlyMaterialsInUseSwitchOnFeaturesAndTheGrid) {
  // A fluorescent, glossy material that no shape uses compiles no fluorescence or gloss and does
  // not extend the grid into the UV.
  Scene s = load(R"({"kasha_scene": 1, "camera": {"position": [0,0,-5], "look_at": [0,0,0]},
    "materials": {"grey": {"passive": {"reflectance": 0.5}},
                  "ink": {"fluorescence": {"excitation": {"nm": [300, 350, 400], "value": [0, 0.2, 0]},
                                           "emission": {"gaussian_nm": 440, "fwhm_nm": 40}},
                          "gloss": {"reflectance": 0.1, "mirror": true}}},
    "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "inward": true,
                "emission": {"line_nm": 365}}]})");
  EXPECT_FALSE(s.fluorescent());
  EXPECT_FALSE(s.glossy());
  EXPECT_EQ(s.grid.min_nm, 380);
}

TEST(Scene, BadScenesGiveOneClearLine) {
  auto check = [](const std::string& text, const std::string& expected) {
    std::string msg = error_of([&] { load(text); });
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  const std::string sphere =
      R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey"})";
  check(scene_with(sphere, R"("colour": 1, )"), "scene.json: /colour: unknown key");
  check(scene_with(R"({"type": "sphere", "center": [0,0,0], "radius": "1", "material": "grey"})"),
        "scene.json: /shapes/0/radius: expected a number, got a string");
  check(scene_with(R"({"type": "sphere", "center": [0,0], "radius": 1, "material": "grey"})"),
        "/shapes/0/center: expected an array of 3 numbers");
  check(scene_with(R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "gold"})"),
        "/shapes/0/material: no material named \"gold\"");
  check(scene_with(R"({"type": "cone", "material": "grey"})"),
        "/shapes/0/type: unknown shape type \"cone\"");
  check(scene_with(R"({"type": "box", "min": [0,0,0], "max": [1,0,1], "material": "grey"})"),
        "must be below");
  check(
      scene_with(
          R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "radius2": 1})"),
      "/shapes/0/radius2: unknown key");
  check(scene_with(R"({"type": "obj", "file": "missing.obj", "material": "grey"})"),
        "missing.obj: cannot read OBJ mesh");
  check(
      scene_with(
          R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "emission": {"nm": [500, 400], "value": [1, 1]}})"),
      "scene.json: /shapes/0/emission: at 400 nm: wavelengths must increase");
  check(scene_with(""), "the scene has no shapes");
  // Beyond float range after a transform (Embree used to abort on these).
  check(
      scene_with(
          R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "transform": {"scale": 1e40}})"),
      "scene.json: /shapes/0: a vertex at (");
  check(
      scene_with(
          R"({"type": "quad", "corner": [1e19,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey"})"),
      "is not finite or beyond ±1e18");
  check(R"({"kasha_scene": 1, "camera": {"position": [0,0,0], "look_at": [0,0,0]}, )" +
            std::string(kMaterials) + R"(, "shapes": [])",
        "scene.json: malformed JSON: parse error at line 1, column");
  check(R"({"kasha_scene": 1, "camera": {"position": [0,0,0], "look_at": [0,0,0]}, )" +
            std::string(kMaterials) + R"(, "shapes": [)" + sphere + "]}",
        "/camera: \"position\" and \"look_at\" are the same point");
  check(scene_with(sphere, R"("wavelengths": {"min_nm": 700, "max_nm": 400}, )"),
        "/wavelengths: min_nm must be below max_nm");
  check(scene_with(sphere, R"("wavelengths": {"bin_nm": -1}, )"),
        "/wavelengths/bin_nm: value -1 is outside");
  EXPECT_NE(error_of([] {
              load_scene("/nonexistent/scene.json");
            }).find("/nonexistent/scene.json: cannot open file"),
            std::string::npos);
}
