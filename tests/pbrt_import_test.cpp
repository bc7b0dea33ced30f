// pbrt-v4 scene import (host/scene/pbrt/, docs/pbrt-import.md):
// - the tokenizer's tokens and lines, parameter lists' types and their errors;
// - transforms against matrices computed by hand, the camera's frame and pbrt-v4's left-handed
//   image, object instances;
// - a pbrt-v4 scene and its kasha JSON twin, written by hand, render the same image bit for bit;
// - lights take pbrt-v4's photometric normalisation: an emitter seen directly shows Y = its
//   `scale` times the RGB's luminance, whatever its spectrum (computed here from the CIE table);
// - named spectra, metals and glasses map to kasha's; --material replaces a named material or
//   an object's; bad input is one line with FILE:LINE, ignored input one warning each.
#include "scene/pbrt/pbrt_import.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "color/cie_observer.h"
#include "film/film.h"
#include "material/glasses.h"
#include "render_support.h"
#include "scene/pbrt/pbrt_parameters.h"
#include "scene/pbrt/pbrt_subdivision.h"
#include "scene/pbrt/pbrt_tokenizer.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

std::vector<PbrtToken> all_tokens(const std::string& text) {
  PbrtTokenizer t(text, "t.pbrt");
  std::vector<PbrtToken> out;
  for (PbrtToken k = t.next(); k.kind != PbrtToken::kEnd; k = t.next()) out.push_back(k);
  return out;
}

PbrtParameters params_of(const std::string& text) {
  PbrtTokenizer t(text, "p.pbrt");
  return PbrtParameters::read(t);
}

nlohmann::json import_text(const std::string& name, const std::string& text,
                           const std::vector<MaterialOverride>& overrides = {}) {
  return import_pbrt_scene(write_file(name, text), overrides);
}

// A scene around `body`: a camera, and a floor when the body has no shape of its own.
std::string scene(const std::string& body) {
  return "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
         "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n" +
         body + "\n";
}

const char* kQuad = R"(Shape "trianglemesh" "point3 P" [-1 0 -1  1 0 -1  1 0 1  -1 0 1]
    "integer indices" [0 1 2  0 2 3])";

std::vector<double> matrix_of(const nlohmann::json& shape) {
  return shape.at("transform").at("matrix").get<std::vector<double>>();
}

void expect_matrix(const std::vector<double>& got, const std::vector<double>& want,
                   const std::string& label) {
  ASSERT_EQ(got.size(), 16u) << label;
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(got[i], want[i], 1e-12) << label << " element " << i;
}

}  // namespace

TEST(PbrtTokenizer, WordsStringsBracketsAndCommentsWithTheirLines) {
  const auto t = all_tokens(
      "Shape \"sphere\" # a comment \"not a string\"\n"
      "  \"float radius\" [ 2.5e-1 ]\n\"a \\\"quoted\\\" \\\\ word\"");
  ASSERT_EQ(t.size(), 7u);
  EXPECT_EQ(t[0].kind, PbrtToken::kWord);
  EXPECT_EQ(t[0].text, "Shape");
  EXPECT_EQ(t[1].kind, PbrtToken::kString);
  EXPECT_EQ(t[1].text, "sphere");
  EXPECT_EQ(t[1].where.line, 1);
  EXPECT_EQ(t[2].text, "float radius");
  EXPECT_EQ(t[2].where.line, 2);
  EXPECT_EQ(t[3].kind, PbrtToken::kOpen);
  EXPECT_EQ(t[4].text, "2.5e-1");
  EXPECT_EQ(t[5].kind, PbrtToken::kClose);
  EXPECT_EQ(t[6].text, "a \"quoted\" \\ word");
  EXPECT_EQ(t[6].where.line, 3);
  EXPECT_EQ(t[6].where.str(), "t.pbrt:3");
  EXPECT_EQ(error_of([] { all_tokens("Shape\n\n\"sphere"); }),
            "t.pbrt:3: a string without its closing quote");
  EXPECT_EQ(error_of([] { all_tokens("Shape \"a\\qb\""); }),
            "t.pbrt:1: unknown escape \\q in a string");
  EXPECT_EQ(error_of([] { all_tokens("Sha\x01pe"); }),
            "t.pbrt:1: a control byte \\x01 in the file");
}

TEST(PbrtParameters, TypedValuesAndTheirErrors) {
  PbrtParameters p = params_of(
      "\"float a\" 1.5 \"rgb c\" [0.1 0.2 0.3] \"bool b\" \"true\" \"bool d\" false "
      "\"integer n\" [3] \"string s\" \"x\" \"point p\" [1 2 3] \"spectrum sp\" [400 1 500 2] "
      "\"color old\" [1 1 1] Shape");
  EXPECT_EQ(p.get_float("a", 0), 1.5);
  EXPECT_EQ(p.get_float("absent", 7), 7);
  EXPECT_TRUE(p.get_bool("b", false));
  EXPECT_FALSE(p.get_bool("d", true));
  EXPECT_EQ(p.get_int("n", 0), 3);
  EXPECT_EQ(p.get_string("s", ""), "x");
  EXPECT_EQ((*p.get_triple("p"))[2], 3);  // "point" is pbrt's older name of point3
  EXPECT_EQ(p.find("sp", "spectrum")->numbers.size(), 4u);
  EXPECT_EQ(p.find("old", "rgb")->type, "rgb");  // "color" is rgb
  EXPECT_EQ(error_of([&] { p.get_float("c", 0); }),
            "p.pbrt:1: \"rgb c\": \"c\" takes a value of type float");

  EXPECT_EQ(error_of([] { params_of("\"float\" 1"); }),
            "p.pbrt:1: \"float\" is not a parameter declaration (\"type name\")");
  EXPECT_EQ(error_of([] { params_of("\"quux a\" 1"); }),
            "p.pbrt:1: \"quux a\": unknown parameter type \"quux\"");
  EXPECT_EQ(error_of([] { params_of("\"point3 p\" [1 2]"); }),
            "p.pbrt:1: \"point3 p\" needs its values in groups of 3");
  EXPECT_EQ(error_of([] { params_of("\"float a\" [1 2"); }),
            "p.pbrt:1: \"float a\": a list without its \"]\"");
  EXPECT_EQ(error_of([] { params_of("\"float a\" 1 \"float a\" 2"); }),
            "p.pbrt:1: parameter \"a\" given twice");
  EXPECT_EQ(error_of([] { params_of("\"float a\" nan"); }),
            "p.pbrt:1: \"float a\": \"nan\" is not a finite number");
  EXPECT_EQ(error_of([] { params_of("\"bool a\" yes"); }),
            "p.pbrt:1: \"bool a\": \"yes\" is not true or false");
  EXPECT_EQ(error_of([] { params_of("\"spectrum s\" [400 1 500]"); }),
            "p.pbrt:1: \"spectrum s\" needs wavelength-value pairs");
  EXPECT_EQ(error_of([] { params_of("\"float a\" [1 2]").get_float("a", 0); }),
            "p.pbrt:1: \"float a\" takes one value, not 2");
}

TEST(PbrtImport, TransformsMatchMatricesComputedByHand) {
  const nlohmann::json s = import_text("t.pbrt", scene(std::string(R"(
AttributeBegin
  Translate 1 2 3
  Rotate 90 0 0 1
  Scale 2 3 4
  )") + kQuad + R"(
AttributeEnd
AttributeBegin
  Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]
  ConcatTransform [0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1]
  CoordinateSystem "here"
  Identity
  CoordSysTransform "here"
  )" + kQuad + R"(
AttributeEnd
ObjectBegin "thing"
  Translate 0 0 1
  )" + kQuad + R"(
ObjectEnd
AttributeBegin
  Scale 2 2 2
  ObjectInstance "thing"
AttributeEnd
)" + kQuad));
  const nlohmann::json& shapes = s.at("shapes");
  ASSERT_EQ(shapes.size(), 3u);
  // T(1,2,3) · Rz(90°) · S(2,3,4): x → 2y, y → −3x, z → 4z, then the translation.
  expect_matrix(matrix_of(shapes[0]), {0, -3, 0, 1, 2, 0, 0, 2, 0, 0, 4, 3, 0, 0, 0, 1},
                "Translate Rotate Scale");
  // pbrt's matrices are column-major: translation (5, 6, 7), then a rotation x → y.
  expect_matrix(matrix_of(shapes[1]), {0, -1, 0, 5, 1, 0, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1},
                "Transform ConcatTransform CoordSysTransform");
  // The instance is kept (docs/formats.md#instances): its transform S(2), and the object's shape
  // under its own T(0, 0, 1).
  expect_matrix(matrix_of(s.at("instances").at(0)),
                {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1}, "ObjectInstance");
  expect_matrix(matrix_of(s.at("objects").at("thing").at(0)),
                {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1}, "ObjectBegin");
  EXPECT_FALSE(shapes[2].contains("transform")) << "AttributeEnd restores the identity";

  // LookAt from +z towards the origin: pbrt-v4's image right is −x (its frame is left-handed),
  // kasha's would be +x: the camera is mirrored.
  const nlohmann::json& cam = s.at("camera");
  EXPECT_EQ(cam.at("position"), nlohmann::json({0, 1, 3}));
  EXPECT_EQ(cam.at("look_at"), nlohmann::json({0, 1, 2}));
  EXPECT_EQ(cam.at("mirror"), true);
  EXPECT_EQ(cam.at("fov_deg"), 45);
  EXPECT_EQ(cam.at("width"), 8);
  // `Scale -1 1 1` before LookAt (a common way to a right-handed pbrt scene) unmirrors it.
  const nlohmann::json r =
      import_text("r.pbrt", "Scale -1 1 1\n" + scene(kQuad));  // the LookAt comes after the Scale
  EXPECT_EQ(r.at("camera").at("mirror"), false);
}

TEST(PbrtImport, ATwinJsonSceneRendersTheSameImageBitForBit) {
  // The lamp's constant spectrum over 300–800 nm, divided by ∫ȳ as pbrt-v4 divides a light's
  // spectrum (SpectrumToPhotometric: 1 nm steps over 360–830 nm).
  const SpectrumPtr& ybar = cie_cmf(Observer::cie1931_2deg)[1];
  double y = 0;
  for (int nm = 360; nm <= 830; ++nm) y += ybar->value(nm) * (nm <= 800 ? 1.0 : 0.0);
  char scale[64];
  std::snprintf(scale, sizeof scale, "%.17g", 8 / y);
  const std::string pbrt = write_file("twin.pbrt", R"(LookAt 0 1 3  0 1 0  0 1 0
Camera "perspective" "float fov" 45
Film "rgb" "integer xresolution" 24 "integer yresolution" 16
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "spectrum L" [300 1 800 1] "float scale" 8
  Material "diffuse" "float reflectance" 0
  Shape "trianglemesh" "point3 P" [-0.25 1.75 -0.25  0.25 1.75 -0.25  0.25 1.75 0.25  -0.25 1.75 0.25]
      "integer indices" [0 1 2  0 2 3]
AttributeEnd
MakeNamedMaterial "grey" "string type" "diffuse" "rgb reflectance" [0.5 0.5 0.5]
MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [0.6 0.1 0.1]
NamedMaterial "grey"
Shape "trianglemesh" "point3 P" [-1 0 -1  -1 0 1  1 0 1  1 0 -1] "integer indices" [0 1 2  0 2 3]
Shape "trianglemesh" "point3 P" [-1 0 -1  1 0 -1  1 2 -1  -1 2 -1] "integer indices" [0 1 2  0 2 3]
NamedMaterial "red"
AttributeBegin
  Translate -1 0 0
  Shape "trianglemesh" "point3 P" [0 0 -1  0 2 -1  0 2 1  0 0 1] "integer indices" [0 1 2  0 2 3]
AttributeEnd
)");
  const std::string json = write_file("twin.json", std::string(R"({"kasha_scene": 1,
  "camera": {"position": [0, 1, 3], "look_at": [0, 1, 2], "up": [0, 1, 0], "fov_deg": 45,
             "width": 24, "height": 16, "mirror": true,
             "filter": {"type": "gaussian", "radius": [1.5, 1.5], "sigma": 0.5}},
  "materials": {"lamp": {"passive": {"reflectance": 0}},
                "grey": {"passive": {"reflectance": {"rgb": [0.5, 0.5, 0.5]}}},
                "red": {"passive": {"reflectance": {"rgb": [0.6, 0.1, 0.1]}}}},
  "shapes": [
    {"type": "quad", "corner": [-0.25, 1.75, -0.25], "u": [0.5, 0, 0], "v": [0, 0, 0.5],
     "material": "lamp", "emission": {"nm": [300, 800], "value": [1, 1], "scale": )") +
                                                       scale +
                                                       R"(}},
    {"type": "quad", "corner": [-1, 0, -1], "u": [0, 0, 2], "v": [2, 0, 0], "material": "grey"},
    {"type": "quad", "corner": [-1, 0, -1], "u": [2, 0, 0], "v": [0, 2, 0], "material": "grey"},
    {"type": "quad", "corner": [0, 0, -1], "u": [0, 2, 0], "v": [0, 0, 2], "material": "red",
     "transform": {"translate": [-1, 0, 0]}}]})");
  RenderSettings s;
  s.spectral = false;
  s.passes = 2;
  const RenderResult a = render_scene(pbrt, s), b = render_scene(json, s);
  ASSERT_EQ(a.image.xyz.size(), b.image.xyz.size());
  EXPECT_TRUE(a.image.xyz == b.image.xyz) << "the pbrt-v4 scene and its twin differ";
  // pbrt-v4's image has the red wall (x = −1) on the right: its camera looks down −z with +x
  // to its left.
  double left = 0, right = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 3; x <= 6; ++x) {  // where the side walls are seen (beyond them: nothing)
      const size_t l = (size_t(y) * 24 + x) * 3, r = (size_t(y) * 24 + 23 - x) * 3;
      left += a.image.xyz[l] - a.image.xyz[l + 2];  // X − Z: red
      right += a.image.xyz[r] - a.image.xyz[r + 2];
    }
  EXPECT_GT(right, left + 0.1) << "the red wall is not on the image's right";
}

// An emitter filling the view, seen directly: pbrt-v4 divides every light's spectrum by its
// photometric integral (an RGB illuminant by its D65's alone), so the film's Y is `scale` times
// the RGB's luminance (1 for a spectrum): 683·Y nits.
TEST(PbrtImport, LightsTakePbrtV4sPhotometricScale) {
  struct Case {
    std::string l;
    double y;
  };
  const double y_rgb = 0.2126 * 0.2 + 0.7152 * 0.5 + 0.0722 * 0.1;  // sRGB luminance
  for (const Case& c : {Case{"\"rgb L\" [1 1 1]", 1.0},
                        Case{"\"rgb L\" [0.2 0.5 0.1] \"float scale\" 2", 2 * y_rgb},
                        Case{"\"blackbody L\" 3000 \"float scale\" 3", 3.0},
                        Case{"\"spectrum L\" \"stdillum-A\"", 1.0},
                        Case{"\"spectrum L\" [420 1 640 1] \"float scale\" 0.5", 0.5}}) {
    const std::string file = write_file("lamp.pbrt", R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 20
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" )" + c.l + R"(
  Shape "trianglemesh" "point3 P" [-5 -5 2  5 -5 2  5 5 2  -5 5 2] "integer indices" [0 2 1  0 3 2]
AttributeEnd
)");
    RenderSettings s;
    s.spectral = false;
    s.passes = 1;
    const RenderResult r = render_scene(file, s);
    double x = 0, y = 0, z = 0;
    for (size_t p = 0; p < r.image.pixels(); ++p) {
      x += r.image.xyz[3 * p] / r.image.pixels();
      y += r.image.xyz[3 * p + 1] / r.image.pixels();
      z += r.image.xyz[3 * p + 2] / r.image.pixels();
    }
    // The film's 10 nm bins against pbrt-v4's 1 nm sum: a few parts in 10⁴; the RGB spectra
    // within kasha's sigmoid fit.
    EXPECT_NEAR(y, c.y, 0.005 * c.y) << c.l;
    if (c.l == "\"rgb L\" [1 1 1]") {  // D65's chromaticity: white in sRGB
      EXPECT_NEAR(x / y, 0.95047, 0.005);
      EXPECT_NEAR(z / y, 1.08883, 0.005);
    }
  }
}

TEST(PbrtImport, NamedSpectraMetalsAndGlassesMapToKashas) {
  const nlohmann::json s = import_text("n.pbrt", scene(R"(
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.1
MakeNamedMaterial "copper" "string type" "conductor"
MakeNamedMaterial "bk7" "string type" "dielectric" "spectrum eta" "glass-BK7"
MakeNamedMaterial "file" "string type" "dielectric" "spectrum eta" "data/n.spd"
MakeNamedMaterial "coat" "string type" "coateddiffuse" "rgb reflectance" [0.2 0.3 0.4] "float roughness" 0.1
NamedMaterial "gold"
)" + std::string(kQuad)));
  const nlohmann::json& m = s.at("materials");
  EXPECT_EQ(m.at("gold"),
            nlohmann::json::parse(
                R"({"conductor": {"metal": "Au", "roughness": 0.1, "remap_roughness": true}})"));
  EXPECT_EQ(m.at("copper").at("conductor").at("metal"), "Cu");  // pbrt-v4's default conductor
  EXPECT_EQ(m.at("bk7").at("dielectric").at("eta"), "BK7");
  EXPECT_EQ(m.at("file").at("dielectric").at("eta"),
            nlohmann::json::parse(R"({"csv": "data/n.spd"})"));
  EXPECT_EQ(m.at("coat").at("coat"),
            nlohmann::json::parse(
                R"({"eta": 1.5, "thickness": 0.01, "roughness": 0.1, "remap_roughness": true})"));
  EXPECT_EQ(m.at("coat").at("passive").at("reflectance"),
            nlohmann::json::parse(R"({"rgb": [0.2, 0.3, 0.4]})"));
}

// pbrt-v4's other named spectra (util/spectrum.cpp's tables, host/data/SOURCES.md): glasses,
// metals, the CIE F series and ACES' D60.
TEST(PbrtImport, EveryNamedSpectrumOfPbrtV4ButTheCameraSensorsIsKashas) {
  const nlohmann::json s = import_text("n2.pbrt", scene(R"(
LightSource "infinite" "spectrum L" "stdillum-F5"
LightSource "point" "spectrum I" "illum-acesD60"
MakeNamedMaterial "baf" "string type" "dielectric" "spectrum eta" "glass-BAF10"
MakeNamedMaterial "sf5" "string type" "dielectric" "spectrum eta" "glass-F5"
MakeNamedMaterial "brass" "string type" "conductor" "spectrum eta" "metal-CuZn-eta" "spectrum k" "metal-CuZn-k"
NamedMaterial "brass"
)" + std::string(kQuad)));
  const nlohmann::json& m = s.at("materials");
  EXPECT_EQ(m.at("baf").at("dielectric").at("eta"), "BAF10");
  EXPECT_EQ(m.at("sf5").at("dielectric").at("eta"), "SF5");
  EXPECT_EQ(m.at("brass").at("conductor").at("metal"), "CuZn");
  const Scene loaded = load_scene(write_file("n2.pbrt", scene(R"(
LightSource "infinite" "spectrum L" "stdillum-F5"
LightSource "point" "spectrum I" "illum-acesD60"
Material "dielectric" "spectrum eta" "glass-LASF9"
)" + std::string(kQuad))));
  EXPECT_EQ(loaded.lights.size(), 2u);
  // LASF9's index at 587.6 nm (n_d), Schott's catalogue: 1.85025; pbrt-v4's table, linear.
  EXPECT_NEAR(named_glass("LASF9")->value(587.56), 1.850, 2e-3);
  EXPECT_NEAR(named_glass("BAF10")->value(587.56), 1.670, 2e-3);
}

// Textures of textures (pbrt_textures.cpp): a reflectance scaled above 1 and a scaled float
// texture become kasha's scale textures (programs) instead of refusals; a 3D texture keeps the
// transform where it was defined.
TEST(PbrtImport, ScaledTexturesAndTexturesOfTexturesBecomeKashaTextures) {
  const nlohmann::json s = import_text("tt.pbrt", scene(R"(
Texture "img" "spectrum" "imagemap" "string filename" "print.png"
Texture "bright" "spectrum" "scale" "texture tex" "img" "float scale" 1.5
Texture "ink" "float" "imagemap" "string filename" "ink.png" "float scale" 0.5
AttributeBegin
Scale 2 2 2
Texture "noise" "float" "fbm" "integer octaves" 4
AttributeEnd
Texture "cloudy" "spectrum" "mix" "texture tex1" "bright" "rgb tex2" [0.1 0.2 0.3] "texture amount" "noise"
Texture "polka" "spectrum" "dots" "rgb inside" [1 0 0] "rgb outside" [0 0 1]
MakeNamedMaterial "a" "string type" "diffuse" "texture reflectance" "bright"
MakeNamedMaterial "b" "string type" "diffuse" "texture reflectance" "cloudy"
MakeNamedMaterial "m" "string type" "mix" "string materials" ["a" "b"] "texture amount" "ink"
NamedMaterial "m"
)" + std::string(kQuad)));
  const nlohmann::json& t = s.at("textures");
  const std::string bright = s.at("materials").at("a").at("textures").at("reflectance");
  EXPECT_EQ(t.at(bright).at("type"), "scale");
  EXPECT_EQ(t.at(bright).at("scale"), 1.5);
  EXPECT_EQ(t.at(bright).at("tex").at("texture"), "pbrt spectrum texture img");
  const std::string ink = s.at("materials").at("m").at("mix").at("amount");
  EXPECT_EQ(t.at(ink).at("type"), "scale");
  EXPECT_EQ(t.at(ink).at("scale"), 0.5);
  const nlohmann::json& cloudy = t.at("pbrt spectrum texture cloudy");
  EXPECT_EQ(cloudy.at("type"), "mix");
  EXPECT_EQ(cloudy.at("tex1").at("texture"), bright);
  EXPECT_EQ(cloudy.at("amount").at("texture"), "pbrt float texture noise");
  expect_matrix(t.at("pbrt float texture noise").at("transform").at("matrix"),
                {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1}, "fbm");
  // pbrt-v4 hands "inside" to the dots' background (DotsTexture::Create's argument order).
  const nlohmann::json& polka = t.at("pbrt spectrum texture polka");
  EXPECT_EQ(polka.at("outside").at("rgb"), (std::vector<double>{1, 0, 0}));
}

// pbrt-v4's imaging ratio, exposure time × ISO / 100 (PixelSensor::Create), scales the image.
TEST(PbrtImport, FilmIsoAndShutterTimeAreTheCamerasExposure) {
  const nlohmann::json s = import_text(
      "e.pbrt",
      "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float shutterclose\" 0.5\n"
      "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8 \"float iso\" 400\n"
      "WorldBegin\n" +
          std::string(kQuad) + "\n");
  EXPECT_DOUBLE_EQ(s.at("camera").at("exposure").get<double>(), 2.0);
  EXPECT_FALSE(import_text("e1.pbrt", scene(kQuad)).at("camera").contains("exposure"));
  // The film applies it to every value it writes.
  WavelengthGrid grid{380, 10, 40};
  Film plain(2, 1, grid, false), bright(2, 1, grid, false, 2.0);
  PassResult pass;
  pass.samples = 4;
  pass.sums = {0.25, 1.25, 2.25, 3.25, 4.25, 5.25};
  plain.accumulate(pass);
  bright.accumulate(pass);
  for (size_t i = 0; i < 6; ++i)
    EXPECT_FLOAT_EQ(bright.image().xyz[i], 2 * plain.image().xyz[i]) << i;
}

// An environment image's transform as pbrt-v4 applies it to directions: its 3 × 3 part, so a
// projective bottom row (pbrt-v4-scenes' sssdragon) changes nothing; StartTime transforms move
// the scene (motion blur), which kasha renders still, with a warning.
TEST(PbrtImport, EnvironmentTransformsAreDirectionsAndStartTimeMotionWarns) {
  write_file("sky.pfm", std::string("PF\n1 1\n-1\n") + std::string(12, '\0'));
  const nlohmann::json s = import_text("d.pbrt", scene(R"(
AttributeBegin
ConcatTransform [-0.224951 0 -0.97437 0 -0.97437 0 0.224951 0 0 1 0 8.87 0 0 0 1]
LightSource "infinite" "string filename" "sky.pfm"
AttributeEnd
)" + std::string(kQuad)));
  const std::vector<double> m = s.at("lights").at(0).at("transform").at("matrix");
  EXPECT_EQ(std::vector<double>(m.begin() + 12, m.end()), (std::vector<double>{0, 0, 0, 1}));
  const std::string file = write_file("moving.pbrt", scene("ActiveTransform StartTime\n"
                                                           "Translate 0 1 0\n"
                                                           "ActiveTransform All\n" +
                                                           std::string(kQuad)));
  CommandResult r = run_kasha("info " + file);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(file + ":6: motion blur is not built in kasha"), std::string::npos) << r.err;
}

TEST(PbrtImport, BadInputIsOneLineWithItsFileAndLine) {
  struct Case {
    std::string body, message;
  };
  const std::vector<Case> cases = {
      {"Frobnicate 1", "b.pbrt:5: unknown directive \"Frobnicate\""},
      {"Shape \"teapot\"", "b.pbrt:5: unknown shape type \"teapot\""},
      {"Material \"measured\"", "b.pbrt:5: material \"measured\" is not built in kasha"},
      {"Material \"diffuse\" \"texture reflectance\" \"nope\"",
       "b.pbrt:5: \"texture reflectance\": no spectrum texture named \"nope\" was defined before"},
      {"MediumInterface \"fog\" \"\"\n" + std::string(kQuad),
       "b.pbrt:6: no medium named \"fog\" (MakeNamedMedium)"},
      {"MakeNamedMedium \"smoke\" \"string type\" \"cloud\"\nMediumInterface \"smoke\" \"\"\n" +
           std::string(kQuad),
       "b.pbrt:7: MakeNamedMedium \"smoke\" ("},  // (its FILE:LINE) is a "cloud" medium …
      {"AttributeEnd", "b.pbrt:5: AttributeEnd without its AttributeBegin"},
      {"AttributeBegin", "b.pbrt:5: AttributeBegin without its AttributeEnd"},
      {"Include \"missing.pbrt\"", "b.pbrt:5: "},
      {"NamedMaterial \"nope\"\n" + std::string(kQuad),
       "b.pbrt:5: NamedMaterial \"nope\": no material of that name"},
      {"LightSource \"goniometric\"",
       "b.pbrt:5: LightSource \"goniometric\" is not built in kasha"},
      {"Translate 1 2 x", "b.pbrt:5: Translate: \"x\" is not a finite number"},
      {"Rotate 30 0 0 0", "b.pbrt:5: Rotate about a zero axis"},
      {"Scale 0 1 1\n" + std::string(kQuad),
       "b.pbrt:6: the shape's transform is singular or projective"},
      {"Shape \"sphere\" \"float radius\" -1", "b.pbrt:5: \"radius\" must be positive"},
      {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 3]",
       "b.pbrt:5: Shape \"trianglemesh\": index 3"},
      {"Material \"diffuse\" \"rgb reflectance\" [2 0 0]",
       "b.pbrt:5: \"rgb reflectance\" has a component above 1 (a reflectance)"},
      {"Material \"conductor\" \"spectrum eta\" \"metal-Zz-eta\" \"spectrum k\" \"metal-Zz-k\"",
       "b.pbrt:5: \"spectrum eta\": the named spectrum \"metal-Zz-eta\" is not among kasha's"},
      {"", "b.pbrt: the scene has no shape that kasha renders"},
  };
  for (const Case& c : cases) {
    const std::string file = write_file("b.pbrt", scene(c.body));
    const std::string e = error_of([&] { load_scene(file); });
    const std::string tail = e.substr(e.find("b.pbrt"));
    EXPECT_EQ(tail.rfind(c.message, 0), 0u) << c.body << "\n  got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  // A file that includes itself stops at the nesting bound.
  const std::string loop = write_file("loop.pbrt", "Include \"loop.pbrt\"\n");
  EXPECT_NE(error_of([&] { load_scene(loop); }).find("Include nested deeper than 32 files"),
            std::string::npos);
  // Through the command line: one line, exit 1, no image.
  const std::string out = (scratch_dir() / "bad.exr").string();
  const std::string bad = write_file("bad.pbrt", scene("Shape \"teapot\""));
  CommandResult r = run_kasha("render " + bad + " --passes 1 -o " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "kasha: error: " + bad +
                ":5: unknown shape type \"teapot\" (kasha reads "
                "trianglemesh, plymesh, bilinearmesh, loopsubdiv, sphere, cylinder, disk)\n");
  EXPECT_FALSE(std::ifstream(out).good());
}

TEST(PbrtImport, WhatKashaIgnoresIsOneWarningEachWithItsLine) {
  const std::string file = write_file("w.pbrt", std::string(R"(LookAt 0 1 3  0 1 0  0 1 0
Camera "orthographic" "float lensradius" 0.1
Sampler "halton" "integer pixelsamples" 16
Film "rgb" "integer xresolution" 8 "integer yresolution" 8 "string sensor" "canon_eos_5d_mkiv"
WorldBegin
Material "diffuse" "float sigma" 20
)") + kQuad + "\n");
  CommandResult r = run_kasha("info " + file);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& line :
       {file + ":2: the orthographic camera's lens is not built in kasha",
        file + ":3: Sampler \"halton\" is ignored",
        file + ":4: the film's \"sensor\" and \"whitebalance\" are not built in kasha",
        file + ":6: \"float sigma\" of Material \"diffuse\" is ignored by kasha"})
    EXPECT_NE(r.err.find("kasha: warning: " + line), std::string::npos) << line << "\n" << r.err;
}

// imagemap as pbrt-v4 reads it: its encoding kept for a PNG (pbrt-v4 applies it to PNGs only),
// octahedralsphere wrap, invert of the scaled value, trilinear and EWA approximated with one
// warning per scene; an environment image under a mirror and a shear, pbrt-v4's directions.
TEST(PbrtImport, ImagemapsAndEnvironmentsTakePbrtV4sParameters) {
  const unsigned char px[12] = {0, 50, 100, 150, 200, 250, 10, 20, 30, 40, 50, 60};
  ASSERT_TRUE(stbi_write_png((scratch_dir() / "tex.png").string().c_str(), 2, 2, 3, px, 6));
  ASSERT_TRUE(stbi_write_tga((scratch_dir() / "tex.tga").string().c_str(), 2, 2, 3, px));
  ASSERT_TRUE(stbi_write_hdr((scratch_dir() / "env.hdr").string().c_str(), 1, 1, 3,
                             std::vector<float>{1, 2, 3}.data()));
  const std::string file = write_file("tex.pbrt", scene(std::string(R"(
Texture "a" "spectrum" "imagemap" "string filename" "tex.png" "string filter" "trilinear"
  "string encoding" "gamma 2.2" "string wrap" "octahedralsphere"
Texture "b" "spectrum" "imagemap" "string filename" "tex.tga" "string filter" "ewa"
  "bool invert" true "float scale" 0.5
Texture "c" "spectrum" "imagemap" "string filename" "tex.tga" "string filter" "trilinear"
Material "diffuse" "texture reflectance" "a"
AttributeBegin
  Scale 1 1 -1
  ConcatTransform [1 0 0 0  0.5 1 0 0  0 0 2 0  0 0 0 1]
  LightSource "infinite" "string filename" "env.hdr"
AttributeEnd
)") + kQuad));
  const nlohmann::json s = import_pbrt_scene(file, {});
  const nlohmann::json& a = s.at("textures").at("pbrt spectrum texture a");
  EXPECT_EQ(a.at("encoding"), "gamma 2.2");
  EXPECT_EQ(a.at("wrap"), "octahedral_sphere");
  EXPECT_EQ(a.at("filter"), "bilinear");
  const nlohmann::json& b = s.at("textures").at("pbrt spectrum texture b");
  EXPECT_FALSE(b.contains("encoding"));
  EXPECT_EQ(b.at("invert"), true);
  EXPECT_EQ(b.at("scale"), 0.5);
  expect_matrix(s.at("lights")[0].at("transform").at("matrix").get<std::vector<double>>(),
                {1, 0.5, 0, 0, 0, 1, 0, 0, 0, 0, -2, 0, 0, 0, 0, 1}, "mirror and shear");
  CommandResult r = run_kasha("info " + file);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  size_t warnings = 0;
  for (size_t at = r.err.find("kasha's bilinear lookup"); at != std::string::npos;
       at = r.err.find("kasha's bilinear lookup", at + 1))
    ++warnings;
  EXPECT_EQ(warnings, 1u) << r.err;
  const std::string bad =
      write_file("enc.pbrt", scene(R"(Texture "d" "spectrum" "imagemap" "string filename" "tex.png"
  "string encoding" "gamma x")"));
  r = run_kasha("info " + bad);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(bad + ":5: texture \"d\": unknown color encoding"), std::string::npos)
      << r.err;
}

TEST(PbrtImport, MaterialOverrideReplacesANamedMaterialOrAnObjectsMaterial) {
  const std::string postit = source_path("scenes/materials/postit.json");
  const std::string file = write_file("o.pbrt", scene(R"(
MakeNamedMaterial "paper" "string type" "diffuse"
NamedMaterial "paper"
)" + std::string(kQuad) + R"(
ObjectBegin "card"
  Material "diffuse"
  Translate 0 1 0
  )" + kQuad + R"(
ObjectEnd
ObjectInstance "card"
)"));
  Scene plain = load_scene(file);
  EXPECT_FALSE(plain.fluorescent());
  Scene named = load_scene(file, std::nullopt, "", {{"paper", postit}});
  EXPECT_TRUE(named.fluorescent());
  EXPECT_EQ(named.material_descs[named.shapes[0].material].name, "paper");
  Scene object = load_scene(file, std::nullopt, "", {{"card", postit}});
  EXPECT_TRUE(object.fluorescent());
  EXPECT_FALSE(object.materials[object.shapes[0].material].fluorescent());
  EXPECT_TRUE(object.materials[object.shapes[1].material].fluorescent());
  EXPECT_NE(error_of([&] {
              load_scene(file, std::nullopt, "", {{"nothing", postit}});
            })
                .find("--material nothing=" + postit + ": " + file +
                      " has no material or object named \"nothing\""),
            std::string::npos);
  // The same option on a kasha JSON scene, through the command line.
  CommandResult r =
      run_kasha("info " + source_path("scenes/cornell_box.json") + " --material white=" + postit);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_kasha("info " + source_path("scenes/cornell_box.json") + " --material white");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("expected NAME=FILE"), std::string::npos) << r.err;
}

// Lights that are not shapes, as pbrt-v4 places and scales them: positions through the current
// transform, `power` as pbrt-v4's k_e (4π for a point light), an environment image square and
// equal-area with its rotation, a uniform sky's spectrum divided by its photometric integral.
TEST(PbrtImport, LightSourcesArePlacedAndScaledAsInPbrtV4) {
  const nlohmann::json s = import_text("l.pbrt", scene(std::string(R"(
AttributeBegin
  Translate 1 2 3
  LightSource "point" "point3 from" [0 1 0] "spectrum I" [400 1 700 1] "float power" 10
  LightSource "spot" "point3 from" [0 0 0] "point3 to" [0 -1 0] "float coneangle" 20 "float conedeltaangle" 4
AttributeEnd
LightSource "distant" "point3 from" [0 1 0] "point3 to" [0 0 0] "rgb L" [1 1 1] "float illuminance" 3
AttributeBegin
  Rotate -90 1 0 0
  LightSource "infinite" "string filename" "sky.exr" "float scale" 2
AttributeEnd
LightSource "infinite" "spectrum L" [400 2 700 2]
)") + kQuad));
  const nlohmann::json& l = s.at("lights");
  ASSERT_EQ(l.size(), 5u);
  const SpectrumPtr& ybar = cie_cmf(Observer::cie1931_2deg)[1];
  double y = 0;  // ∫ȳ of the constant 1 over 400–700 nm, in pbrt-v4's 1 nm steps
  for (int nm = 400; nm <= 700; ++nm) y += ybar->value(nm);
  EXPECT_EQ(l[0].at("type"), "point");
  EXPECT_EQ(l[0].at("position"), nlohmann::json({1, 3, 3}));
  EXPECT_NEAR(l[0].at("intensity").at("scale").get<double>(), 10 / (4 * M_PI) / y, 1e-12 / y);
  EXPECT_EQ(l[1].at("from"), nlohmann::json({1, 2, 3}));
  EXPECT_EQ(l[1].at("to"), nlohmann::json({1, 1, 3}));
  EXPECT_EQ(l[1].at("cone_deg"), 20);
  EXPECT_EQ(l[1].at("cone_delta_deg"), 4);
  EXPECT_EQ(l[1].at("intensity").at("rgb_illuminant"), nlohmann::json({1, 1, 1}));  // D65
  EXPECT_EQ(l[2].at("type"), "distant");
  EXPECT_EQ(l[2].at("irradiance").at("rgb_illuminant"), nlohmann::json({1, 1, 1}));
  const double d65 = l[1].at("intensity").at("scale").get<double>();  // 1 / ∫ȳ D65
  EXPECT_NEAR(l[2].at("irradiance").at("scale").get<double>(), 3 * d65, 1e-15);
  EXPECT_EQ(l[3].at("image"), "sky.exr");
  EXPECT_EQ(l[3].at("mapping"), "equal_area");
  EXPECT_NEAR(l[3].at("scale").get<double>(), 2 * d65, 1e-15);
  // Rx(−90°): y → −z, z → y.
  expect_matrix(l[3].at("transform").at("matrix").get<std::vector<double>>(),
                {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1}, "environment rotation");
  EXPECT_NEAR(l[4].at("radiance").at("scale").get<double>(), 1 / (2 * y), 1e-12 / y);
}

// Loop subdivision (pbrt-v4's loopsubdiv) on the unit octahedron, worked by hand: every vertex has
// valence 4, so β = 3/32 and the limit weight γ = 1/(4 + 3/(8β)) = 1/8; an original vertex v's
// limit point is (1 − 4γ)v + γ·Σ(neighbours) = v/2 (its neighbours sum to 0), and after one level
// (v → 5/8 v, an edge's new vertex 3/8 of its ends) again v/2: the limit surface does not depend on
// the level. A flat open mesh stays flat and keeps its boundary's corners' weights (3/5, 1/5).
TEST(PbrtImport, LoopSubdivisionMatchesTheLimitWorkedByHand) {
  const std::vector<double> p = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  const std::vector<double> idx = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                   2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  for (int levels : {0, 1, 2}) {
    const SubdividedMesh m = loop_subdivide(p, idx, levels);
    ASSERT_EQ(m.indices.size(), 24u * (1u << (2 * levels))) << levels;
    for (int v = 0; v < 6; ++v) {  // the original vertices keep their indices
      const Eigen::Vector3d x(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
      const Eigen::Vector3d want = 0.5 * Eigen::Vector3d(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
      EXPECT_LT((x - want).norm(), 1e-12) << "level " << levels << " vertex " << v;
      const Eigen::Vector3d n(m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2]);
      EXPECT_GT(n.normalized().dot(want.normalized()), 1 - 1e-12) << "outward, along v";
    }
  }
  // Two triangles of a unit square in z = 0: flat, and the corner (0, 0) — two boundary
  // neighbours (1, 0) and (0, 1) — goes to 3/5·(0, 0) + 1/5·((1, 0) + (0, 1)) = (0.2, 0.2).
  const SubdividedMesh sq =
      loop_subdivide({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, 0);
  EXPECT_NEAR(sq.positions[0], 0.2, 1e-12);
  EXPECT_NEAR(sq.positions[1], 0.2, 1e-12);
  const SubdividedMesh flat =
      loop_subdivide({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, 3);
  for (size_t i = 2; i < flat.positions.size(); i += 3) EXPECT_EQ(flat.positions[i], 0);
  // Through the importer: a subdivided octahedron renders as "triangles" with normals.
  const nlohmann::json s = import_text("sub.pbrt", scene(R"(Shape "loopsubdiv" "integer levels" 2
    "point3 P" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1]
    "integer indices" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5])"));
  EXPECT_EQ(s.at("shapes")[0].at("indices").size(), 3u * 8 * 16);
  EXPECT_TRUE(s.at("shapes")[0].contains("normals"));
}
