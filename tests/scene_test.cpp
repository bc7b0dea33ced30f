// Scenes: strict JSON with paths in errors, shapes and their front sides, transforms, camera.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "render_support.h"
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
        "missing.obj: cannot open file");
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
        "scene.json: malformed JSON at line 1, column");
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

namespace {

// One line naming `expected` (a file with its line or JSON path, and the value).
void expect_load_error(const std::string& text, const std::string& expected) {
  std::string msg = error_of([&] { load(text); });
  EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

std::string obj_shape(const std::string& name, const std::string& text,
                      const std::string& extra = "") {
  std::string obj = test::write_file(name, text);
  return R"({"type": "obj", "file": ")" + obj + R"(", "material": "grey")" + extra + "}";
}

const char* kSphere = R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey"})";

}  // namespace

TEST(Scene, EmissionBeyondFloatRangeNamesItsPathAndValue) {
  const std::string lit =
      R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "emission": )";
  expect_load_error(
      scene_with(std::string(kSphere) + ", " + kSphere + ", " + lit +
                 R"({"gaussian_nm": 500, "fwhm_nm": 20, "scale": 1e40}})"),
      "scene.json: /shapes/2/emission/scale: a spectrum value of 1e+40 is beyond 1e30");
  expect_load_error(scene_with(lit + "2e30}"),
                    "scene.json: /shapes/0/emission: a spectrum value of 2e+30 is beyond 1e30");
  std::string csv = test::write_file("lamp.csv", "400,1\n500,1e35\n600,1\n");
  expect_load_error(scene_with(lit + R"({"csv": ")" + csv + R"("}})"),
                    "lamp.csv: line 2: at 500 nm: a spectrum value of 1e+35 is beyond 1e30");
  // Beyond double range the JSON parser refuses the number itself (it has no path yet).
  expect_load_error(scene_with(lit + R"({"nm": [400, 500], "value": [1, 1e400]}})"),
                    "scene.json: malformed JSON: number overflow parsing '1e400'");
  // A material's spectra are spectra too.
  expect_load_error(
      R"({"kasha_scene": 1, )" + std::string(kCamera) +
          R"(, "materials": {"grey": {"passive": {"reflectance": 1e31}}}, "shapes": [)" + kSphere +
          "]}",
      "scene.json: /materials/grey/passive/reflectance: a spectrum value of 1e+31");
}

TEST(Scene, EmitterRadianceAndPowerOnTheGridStayInFloatRange) {
  // A line puts its whole integral into one bin: 1e30 over a 0.1 nm bin is 1e31 per nm.
  expect_load_error(
      scene_with(
          R"({"type": "quad", "corner": [0,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey",
              "emission": {"line_nm": 500.05, "scale": 1e30}})",
          R"("wavelengths": {"bin_nm": 0.1}, )"),
      "scene.json: /shapes/0/emission: the radiance of 1e+31 in the bin 500–500.1 nm is beyond "
      "1e30");
  // π·area·∫L = π·1e4 m²·(1e30·400 nm) = 1.26e37 W.
  const std::string wide_lamp =
      R"({"type": "quad", "corner": [0,0,0], "u": [100,0,0], "v": [0,100,0], "material": "grey",
          "emission": 1e30})";
  expect_load_error(
      scene_with(std::string(kSphere) + ", " + wide_lamp),
      "scene.json: /shapes/1/emission: the emitted power of 1.25664e+37 (π·area·∫L) is "
      "beyond 1e35");
  // The same radiance from 1 cm² is 1.26e29 W: fine, and the light CDF uses the same power.
  Scene small = load(scene_with(
      R"({"type": "quad", "corner": [0,0,0], "u": [0.01,0,0], "v": [0,0.01,0], "material": "grey",
          "emission": 1e30})"));
  double power = 0;
  for (const KTriangle& t : small.triangles)
    power += emitted_power(t, small.emitters[0].integrated_radiance(small.grid.bin_nm));
  EXPECT_NEAR(power / (M_PI * 1e-4 * 4e32), 1.0, 1e-6);
  // A lamp of 1e-32 m² would need a light-sampling density of 1e32 per m² in float.
  expect_load_error(
      scene_with(std::string(kSphere) + ", " +
                 R"({"type": "quad", "corner": [0,0,0], "u": [1e-16,0,0], "v": [0,1e-16,0],
                     "material": "grey", "emission": 1})"),
      "scene.json: /shapes/1/emission: the emitting area is too small: light sampling's density "
      "per unit area of 1e+32 is beyond 1e30");
}

TEST(Scene, ObjVerticesAndFacesAreCheckedByLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // tinyobjloader would read these as 0 or (1, 0, 0) without a word.
  expect_load_error(scene_with(obj_shape("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 0 0\nf 1 2 3\n")),
                    "nan.obj: line 3: vertex coordinate \"nan\" is not a finite number");
  expect_load_error(scene_with(obj_shape("inf.obj", "# a mesh\r\nv 0 0 0\r\nv 0 -inf 0\r\n")),
                    "inf.obj: line 3: vertex coordinate \"-inf\" is not a finite number");
  expect_load_error(scene_with(obj_shape("short.obj", "v 0 0 0\nv 1\nv 0 1 0\nf 1 2 3\n")),
                    "short.obj: line 2: a vertex needs x, y and z, found 1 number");
  expect_load_error(scene_with(obj_shape("hex.obj", "v 0 0 0\nv 0x10 0 0\n")),
                    "hex.obj: line 2: vertex coordinate \"0x10\" is not a finite number");
  // Finite in double but beyond float range, or beyond ±1e18.
  expect_load_error(scene_with(obj_shape("far.obj", tri + "v 0 1e19 0\nf 1 2 4\n")),
                    "far.obj: line 4: a vertex at (0, 1e+19, 0) is beyond ±1e18");
  expect_load_error(scene_with(obj_shape("huge.obj", "v 1e39 0 0\n")),
                    "huge.obj: line 1: a vertex at (1e+39, 0, 0) is beyond ±1e18");
  // Faces name vertices defined above them (negative ones count back from the last).
  expect_load_error(scene_with(obj_shape("face.obj", tri + "f 1 2 4\n")),
                    "face.obj: line 4: face vertex \"4\" names no vertex (3 defined above it)");
  expect_load_error(scene_with(obj_shape("penta.obj", tri + "f 1 2 3 9 10\n")),
                    "penta.obj: line 4: face vertex \"9\" names no vertex (3 defined above it)");
  expect_load_error(scene_with(obj_shape("back.obj", tri + "f -4 -2 -1\n")),
                    "back.obj: line 4: face vertex \"-4\" names no vertex");
  expect_load_error(scene_with(obj_shape("zero.obj", tri + "f 0 1 2\n")),
                    "zero.obj: line 4: face vertex \"0\" names no vertex");
  expect_load_error(scene_with(obj_shape("later.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n")),
                    "later.obj: line 2: face vertex \"2\" names no vertex (1 defined above it)");
  // What is valid still loads: relative indices, normals, texture coordinates, w, comments.
  Scene s = load(scene_with(obj_shape(
      "good.obj", "# ok\nv 0 0 0 1\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf -3/1/1 -2/1/1 -1//1\n")));
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_FLOAT_EQ(s.triangles[0].v1[0], 1.0f);
}

TEST(Scene, ZeroAreaAndDuplicateTrianglesAreHarmless) {
  // An emitting mesh facing the camera (+z) inside a box: two good triangles, one with a repeated
  // vertex, one that is a point, two collinear ones, and a good one twice over.
  const std::string mesh =
      "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nv 0 0 1\nv 2 2 1\n"
      "f 1 2 3\nf 1 3 4\nf 1 3 3\nf 5 5 5\nf 1 5 3\nf 1 2 3\nf 5 3 6\n";
  const std::string camera_and_materials =
      std::string(R"({"kasha_scene": 1, "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0],
        "width": 8, "height": 8}, )") +
      kMaterials + R"(, "shapes": [)";
  const std::string enclosure =
      R"(, {"type": "box", "min": [-6,-6,-6], "max": [6,6,6], "material": "grey", "inward": true}]})";
  std::string scene = test::write_file(
      "degenerate.json",
      camera_and_materials + obj_shape("degenerate.obj", mesh, R"(, "emission": 1)") + enclosure);
  Scene s = load_scene(scene);
  const double radiance = s.emitters[0].integrated_radiance(s.grid.bin_nm);
  // The good triangle's twin is left out at load (a coincident twin would double its power).
  ASSERT_EQ(s.shapes[0].triangle_count, 6);
  for (int zero : {2, 3, 4, 5}) EXPECT_EQ(emitted_power(s.triangles[zero], radiance), 0.0) << zero;
  EXPECT_GT(emitted_power(s.triangles[0], radiance), 0.0);
  for (const char* integrator : {"backward", "forward", "photon"}) {
    test::RenderSettings settings;
    settings.integrator = integrator;
    settings.passes = 1;
    settings.spectral = false;
    settings.integrator_settings.spp = 4;
    settings.integrator_settings.photons = 4096;
    test::RenderResult r = test::render_scene(scene, settings);
    double sum = 0;
    for (float x : r.image.xyz) {
      ASSERT_TRUE(std::isfinite(x)) << integrator;
      sum += x;
    }
    EXPECT_GT(sum, 0) << integrator;
  }
  // An emitter whose every triangle has zero area has no power: the physical integrators refuse
  // the scene as before.
  std::string dark = test::write_file(
      "flat.json", camera_and_materials +
                       obj_shape("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 1\n",
                                 R"(, "emission": 1)") +
                       enclosure);
  EXPECT_EQ(load_scene(dark).emitters.size(), 1u);
  test::RenderSettings backward;
  backward.passes = 1;
  EXPECT_NE(error_of([&] { test::render_scene(dark, backward); }).find("no emitter has power"),
            std::string::npos);
}

TEST(Scene, TransformsAndTheCameraStayInsideTheCoordinateRange) {
  const std::string quad =
      R"({"type": "quad", "corner": [0,0,0], "u": [1,0,0], "v": [0,1,0], "material": "grey", )";
  expect_load_error(
      scene_with(quad + R"("transform": {"scale": [1, 1e30, 1]}})"),
      "scene.json: /shapes/0: a vertex at (1, 1e+30, 0) is not finite or beyond ±1e18");
  expect_load_error(
      scene_with(quad + R"("transform": {"translate": [0, 0, 2e18]}})"),
      "scene.json: /shapes/0: a vertex at (0, 0, 2e+18) is not finite or beyond ±1e18");
  expect_load_error(
      scene_with(quad +
                 R"("transform": {"matrix": [1e300,0,0,0, 0,1e300,0,0, 0,0,1e300,0, 0,0,0,1]}})"),
      "scene.json: /shapes/0: a vertex at (1e+300, 0, 0)");
  expect_load_error(
      scene_with(obj_shape("unit.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                           R"(, "transform": {"scale": 1e40})")),
      "scene.json: /shapes/0: a vertex at (1e+40, 0, 0) is not finite or beyond ±1e18");
  auto with_camera = [](const std::string& camera) {
    return R"({"kasha_scene": 1, "camera": )" + camera + ", " + kMaterials + R"(, "shapes": [)" +
           kSphere + "]}";
  };
  expect_load_error(with_camera(R"({"position": [2e18, 0, -5], "look_at": [0, 0, 0]})"),
                    "scene.json: /camera/position: a coordinate of 2e+18 is beyond ±1e18");
  expect_load_error(with_camera(R"({"position": [0, 0, -5], "look_at": [0, -1e30, 0]})"),
                    "scene.json: /camera/look_at: a coordinate of -1e+30 is beyond ±1e18");
  expect_load_error(
      with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1e19, 0]})"),
      "scene.json: /camera/up: a coordinate of 1e+19 is beyond ±1e18");
  expect_load_error(
      with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 0, 0]})"),
      "scene.json: /camera: \"up\" is zero");
  expect_load_error(
      with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_deg": 1e40})"),
      "scene.json: /camera/fov_deg: value 1e+40 is outside");
  // A short but valid "up" is a direction, not parallel to the view.
  Scene s =
      load(with_camera(R"({"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1e-12, 0]})"));
  EXPECT_GT(s.camera.to_kernel().up[1], 0);
}

// Lights and textures (docs/lights.md, docs/textures.md): every mistake one line naming its JSON
// path, nothing rendered.
TEST(Scene, BadLightsAndTexturesGiveOneClearLine) {
  auto check = [](const std::string& extra, const std::string& expected,
                  const std::string& materials = "", const std::string& shape = "") {
    std::string text = R"({"kasha_scene": 1, )" + std::string(kCamera) + ", " +
                       (materials.empty() ? std::string(kMaterials) : materials) + ", " + extra +
                       R"("shapes": [)" + (shape.empty() ? std::string(kSphere) : shape) + "]}";
    std::string msg = error_of([&] { load(text); });
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  check(R"("lights": [{"type": "laser", "intensity": 1}], )",
        "scene.json: /lights/0/type: unknown light type \"laser\"");
  check(R"("lights": [{"type": "point", "intensity": 1, "colour": 2}], )",
        "/lights/0/colour: unknown key");
  check(R"("lights": [{"type": "point"}], )", "/lights/0: missing required key \"intensity\"");
  check(R"("lights": [{"type": "spot", "intensity": 1, "cone_deg": 10, "cone_delta_deg": 20}], )",
        "/lights/0/cone_delta_deg: the falloff is wider than the cone");
  check(R"("lights": [{"type": "distant", "from": [1, 1, 1], "to": [1, 1, 1], "irradiance": 1}], )",
        "/lights/0: \"from\" and \"to\" are the same point");
  check(R"("lights": [{"type": "point", "intensity": -1}], )", "/lights/0/intensity: negative");
  check(R"("lights": [{"type": "infinite", "image": "missing.exr"}], )", "/lights/0/image:");
  check(R"("lights": [{"type": "infinite", "radiance": 1, "image": "sky.exr"}], )",
        "/lights/0/radiance: an infinite light takes \"radiance\" or \"image\", not both");
  check(R"("textures": {"t": {"type": "image", "file": "missing.png"}}, )", "/textures/t/file:");
  check(R"("textures": {"t": {"type": "image", "file": "x.gif"}}, )", "/textures/t/file:");
  check(R"("textures": {"t": {"type": "checkerboard", "even": 1, "odd": 0, "wrap": "mirror"}}, )",
        "/textures/t/wrap: unknown key");
  check(R"("textures": {"t": {"type": "noise"}}, )", "/textures/t/type: unknown texture type");
  check(R"("textures": {"t": {"type": "checkerboard", "even": 1, "odd": 0, "uscale": 0}}, )",
        "/textures/t/uscale: a scale of 0");
  check(
      "", "/materials/grey/textures/reflectance: no texture named \"t\"",
      R"("materials": {"grey": {"passive": {"reflectance": 0.5}, "textures": {"reflectance": "t"}}})");
  const std::string checker =
      R"("textures": {"t": {"type": "checkerboard", "even": 1, "odd": 0.2}}, )";
  check(
      checker,
      "a fluorescence texture scales the material's excitation, and \"grey\" does not fluoresce",
      R"("materials": {"grey": {"passive": {"reflectance": 0.5}, "textures": {"fluorescence": "t"}}})");
  check(
      checker, "a reflectance texture multiplies the material's passive reflectance",
      R"("materials": {"grey": {"gloss": {"reflectance": 0.5}, "textures": {"reflectance": "t"}}})");
  check(
      R"("textures": {"t": {"type": "checkerboard", "even": 2, "odd": 0.2}}, )",
      "/textures/t: a reflectance texture's values multiply a reflectance: at most 1",
      R"("materials": {"grey": {"passive": {"reflectance": 0.5}, "textures": {"reflectance": "t"}}})");
  check(
      checker, "/shapes/0/emission_texture: an emission texture needs the shape's", "",
      R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "emission_texture": "t"})");
  check(
      checker, "/shapes/0/emission_texture: no texture named \"u\"", "",
      R"({"type": "sphere", "center": [0,0,0], "radius": 1, "material": "grey", "emission": 1, "emission_texture": "u"})");
  check("", "/rgb: an RGB component of 1.5 is outside [0, 1]",
        R"("materials": {"grey": {"passive": {"reflectance": {"rgb": [1.5, 0, 0]}}}})");
}
