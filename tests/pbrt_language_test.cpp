// pbrt-v4's scene language as pbrt-v4 reads it (host/scene/pbrt/, docs/pbrt-import.md):
// - each spectrum parameter by pbrt-v4's SpectrumType: an unbounded RGB (a conductor's η and k)
//   is RGBUnboundedSpectrum, 2m · S(table(rgb / 2m)), checked against that formula and against
//   the exact value of a grey (S of a grey is the grey itself); an albedo above 1 is refused;
// - the artist's conductor: η = 1, k = 2√r / √(1 − r);
// - float textures resolve to their constants where kasha takes a number;
// - pbrt-v4's options and world blocks, each refusal one line with FILE:LINE.
#include <gtest/gtest.h>

#include <cmath>

#include "material/metals.h"
#include "scene/pbrt/pbrt_import.h"
#include "scene/scene.h"
#include "spectrum/rgb_spectrum.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

const char* kHeader =
    "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
    "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n";

const char* kQuad = R"(Shape "trianglemesh" "point3 P" [-1 0 -1  1 0 -1  1 0 1  -1 0 1]
    "integer indices" [0 1 2  0 2 3])";

nlohmann::json materials_of(const std::string& body) {
  const std::string file = write_file("lang.pbrt", std::string(kHeader) + body + "\n" + kQuad);
  return import_pbrt_scene(file, {}).at("materials");
}

// The tabulated spectrum's value at nm (it is sampled every nanometre).
double value_at(const nlohmann::json& spectrum, double nm) {
  const auto l = spectrum.at("nm").get<std::vector<double>>();
  const auto v = spectrum.at("value").get<std::vector<double>>();
  for (size_t i = 0; i < l.size(); ++i)
    if (l[i] == nm) return v[i] * spectrum.value("scale", 1.0);
  ADD_FAILURE() << "no sample at " << nm << " nm";
  return NAN;
}

// The line "FILE:LINE: …" of the error `body` (after the 4-line header) gives.
std::string error_tail(const std::string& text) {
  const std::string e = error_of([&] { load_scene(write_file("blocks.pbrt", text)); });
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const size_t at = e.find("blocks.pbrt");
  return at == std::string::npos ? e : e.substr(at);
}

}  // namespace

TEST(PbrtLanguage, UnboundedRgbIsPbrtV4sRgbUnboundedSpectrum) {
  const nlohmann::json m = materials_of(R"(MakeNamedMaterial "m" "string type" "conductor"
    "rgb eta" [0.2 0.9 1.1] "rgb k" [3 3 3])");
  const nlohmann::json& c = m.at("m").at("conductor");
  // pbrt-v4: scale = 2 · max, the albedo table at rgb / scale, times scale.
  const double scale = 2 * 1.1;
  const SigmoidCoefficients coeff = rgb_sigmoid({0.2 / scale, 0.9 / scale, 1.1 / scale});
  for (double nm : {400.0, 550.0, 700.0})
    EXPECT_NEAR(value_at(c.at("eta"), nm), scale * sigmoid_spectrum(coeff, nm), 1e-12) << nm;
  // A grey's sigmoid is the grey: k is 3 at every wavelength.
  for (double nm : {360.0, 500.0, 830.0}) EXPECT_NEAR(value_at(c.at("k"), nm), 3, 1e-9) << nm;
}

TEST(PbrtLanguage, SpectrumTexturesAreReadAsTheirUseReadsThem) {
  const nlohmann::json m = materials_of(R"(
Texture "grey" "spectrum" "constant" "rgb value" [0.4 0.4 0.4]
Texture "bright" "spectrum" "scale" "texture tex" "grey" "float scale" 5
MakeNamedMaterial "m" "string type" "conductor" "texture eta" "grey" "texture k" "bright"
MakeNamedMaterial "d" "string type" "diffuse" "texture reflectance" "grey"
MakeNamedMaterial "b" "string type" "diffuse" "blackbody reflectance" 5000)");
  const nlohmann::json& c = m.at("m").at("conductor");
  EXPECT_NEAR(value_at(c.at("eta"), 550), 0.4, 1e-9);
  EXPECT_NEAR(value_at(c.at("k"), 550), 2.0, 1e-9);  // 0.4 × 5: beyond an albedo, as pbrt-v4 allows
  EXPECT_EQ(m.at("d").at("passive").at("reflectance"),
            nlohmann::json::parse(R"({"rgb": [0.4, 0.4, 0.4]})"));
  // pbrt-v4's BlackbodySpectrum outside a light peaks at 1.
  const nlohmann::json& b = m.at("b").at("passive").at("reflectance");
  EXPECT_EQ(b.at("blackbody_K"), 5000);
  EXPECT_NEAR(b.at("scale").get<double>() * BlackbodySpectrum(5000).peak(), 1, 1e-12);
}

TEST(PbrtLanguage, ArtistsConductorTakesPbrtV4sEtaAndK) {
  const nlohmann::json m = materials_of(R"(
Texture "r" "spectrum" "constant" "rgb value" [0.8 0.8 0.8]
MakeNamedMaterial "half" "string type" "conductor" "rgb reflectance" [0.5 0.5 0.5]
MakeNamedMaterial "tex" "string type" "conductor" "texture reflectance" "r" "float roughness" 0.2)");
  const nlohmann::json& half = m.at("half").at("conductor");
  EXPECT_EQ(half.at("eta"), 1.0);
  for (double nm : {400.0, 600.0}) EXPECT_NEAR(value_at(half.at("k"), nm), 2, 1e-9);  // 2√½/√½
  const nlohmann::json& tex = m.at("tex").at("conductor");
  EXPECT_NEAR(value_at(tex.at("k"), 500), 2 * std::sqrt(0.8) / std::sqrt(0.2), 1e-9);
  EXPECT_EQ(tex.at("roughness"), 0.2);
}

TEST(PbrtLanguage, AConductorGivenEtaOrKAloneTakesCoppersOther) {
  const nlohmann::json m = materials_of(R"(
MakeNamedMaterial "eta" "string type" "conductor" "rgb eta" [0.5 0.5 0.5]
MakeNamedMaterial "k" "string type" "conductor" "spectrum eta" "metal-Au-eta" "float k" 3)");
  const MetalIndex cu = builtin_metal("Cu"), au = builtin_metal("Au");
  for (double nm : {400.0, 633.0}) {
    EXPECT_NEAR(value_at(m.at("eta").at("conductor").at("eta"), nm), 0.5, 1e-9);
    EXPECT_NEAR(value_at(m.at("eta").at("conductor").at("k"), nm), cu.k->value(nm), 1e-12);
    EXPECT_NEAR(value_at(m.at("k").at("conductor").at("eta"), nm), au.eta->value(nm), 1e-12);
  }
  EXPECT_EQ(m.at("k").at("conductor").at("k"), 3.0);
}

TEST(PbrtLanguage, FloatTexturesResolveToTheirConstants) {
  const nlohmann::json m = materials_of(R"(
Texture "r" "float" "constant" "float value" 0.3
Texture "half" "float" "scale" "texture tex" "r" "float scale" 0.5
MakeNamedMaterial "m" "string type" "dielectric" "texture uroughness" "r" "texture vroughness" "half"
MakeNamedMaterial "c" "string type" "coateddiffuse" "texture roughness" "half" "texture thickness" "r"
    "rgb albedo" [0 0 0])");
  const nlohmann::json& d = m.at("m").at("dielectric");
  EXPECT_NEAR(d.at("uroughness").get<double>(), 0.3, 1e-15);
  EXPECT_NEAR(d.at("vroughness").get<double>(), 0.15, 1e-15);
  EXPECT_NEAR(m.at("c").at("coat").at("roughness").get<double>(), 0.15, 1e-15);
  EXPECT_NEAR(m.at("c").at("coat").at("thickness").get<double>(), 0.3, 1e-15);
}

TEST(PbrtLanguage, RefusalsOfTypesAndTexturesNameTheirLine) {
  const std::string h = kHeader;  // four lines: the body starts on line 5
  EXPECT_EQ(error_tail(h + "Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [1.5 1 1]"),
            "blocks.pbrt:5: \"rgb value\" has a component above 1 (a reflectance)");
  EXPECT_EQ(error_tail(h + "Texture \"c\" \"spectrum\" \"checkerboard\"\n"
                           "Material \"conductor\" \"texture reflectance\" \"c\""),
            "blocks.pbrt:6: \"texture reflectance\": a conductor's reflectance texture is not "
            "built in kasha (its η and k take one spectrum each)");
  EXPECT_EQ(error_tail(h + "Material \"coateddiffuse\" \"rgb albedo\" [0.2 0 0]"),
            "blocks.pbrt:5: coateddiffuse: a scattering coat (\"albedo\" > 0) is not built in "
            "kasha");
  EXPECT_EQ(error_tail(h + "Material \"conductor\" \"rgb reflectance\" [0.5 0.5 0.5] "
                           "\"rgb k\" [1 1 1]"),
            "blocks.pbrt:5: conductor: \"reflectance\" and \"eta\"/\"k\" both given (pbrt-v4 "
            "refuses it too)");
}

TEST(PbrtLanguage, OptionsAndWorldBlocksAreKeptAsPbrtV4KeepsThem) {
  EXPECT_EQ(error_tail(std::string("Camera \"perspective\"\n") + kQuad + "\nWorldBegin\n"),
            "blocks.pbrt:2: the scene's description belongs inside the world block: \"Shape\" "
            "before WorldBegin (pbrt-v4 refuses it too)");
  EXPECT_EQ(error_tail("Material \"diffuse\"\nWorldBegin\n"),
            "blocks.pbrt:1: the scene's description belongs inside the world block: "
            "\"Material\" before WorldBegin (pbrt-v4 refuses it too)");
  EXPECT_EQ(error_tail(std::string(kHeader) + "WorldBegin\n"),
            "blocks.pbrt:5: options cannot be set inside the world block: \"WorldBegin\" after "
            "WorldBegin (pbrt-v4 refuses it too)");
  for (const char* option : {"Camera \"perspective\"", "Film \"rgb\"", "Sampler \"halton\"",
                             "Integrator \"path\"", "PixelFilter \"box\"", "Accelerator \"bvh\""}) {
    const std::string name = std::string(option).substr(0, std::string(option).find(' '));
    EXPECT_EQ(error_tail(std::string(kHeader) + kQuad + "\n" + option + "\n"),
              "blocks.pbrt:7: options cannot be set inside the world block: \"" + name +
                  "\" after WorldBegin (pbrt-v4 refuses it too)");
  }
  // Transforms, ColorSpace, Option and Attribute belong to both blocks.
  EXPECT_NO_THROW(load_scene(write_file(
      "both.pbrt", "ColorSpace \"srgb\"\nAttribute \"texture\" \"float scale\" 2\n" +
                       std::string(kHeader) + "ColorSpace \"srgb\"\nTranslate 0 1 0\n" + kQuad)));
}

TEST(PbrtLanguage, ErrorsFoundInTheConvertedSceneNameTheStatement) {
  const std::string h = kHeader;  // four lines: the body starts on line 5
  // Checked by kasha's scene loader, not the importer: each names the pbrt-v4 statement.
  EXPECT_EQ(error_tail(h + "\n" + R"(Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1e39 0])"),
            "blocks.pbrt:6: a vertex at (0, 1e+39, 0) is not finite or beyond ±1e18");
  EXPECT_EQ(error_tail(h + "Material \"dielectric\" \"float eta\" 0\n" + kQuad),
            "blocks.pbrt:5: eta must lie in [0.01, 100] (the index behind the surface over the "
            "one in front)");
  EXPECT_EQ(error_tail(h +
                       "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" "
                       "[300 1e40 900 1e40]\n" +
                       kQuad + "\nAttributeEnd"),
            "blocks.pbrt:6: at 300 nm: a spectrum value of 1e+40 is beyond 1e30");
  const std::string t =
      error_tail(h +
                 "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"a.gif\"\n"
                 "Material \"diffuse\" \"texture reflectance\" \"t\"\n" +
                 kQuad);
  EXPECT_EQ(t.rfind("blocks.pbrt:5: ", 0), 0u) << t;
}

TEST(PbrtLanguage, ColorSpacesGiveTheSameColourInSrgb) {
  const nlohmann::json s =
      import_pbrt_scene(write_file("cs.pbrt", std::string(kHeader) + R"(AttributeBegin
ColorSpace "rec2020"
MakeNamedMaterial "rec" "string type" "diffuse" "rgb reflectance" [0.3 0.4 0.5]
LightSource "point" "rgb I" [1 1 1]
ColorSpace "aces2065-1"
MakeNamedMaterial "aces" "string type" "diffuse" "rgb reflectance" [0.5 0.5 0.5]
LightSource "point" "rgb I" [1 1 1]
AttributeEnd
MakeNamedMaterial "back" "string type" "diffuse" "rgb reflectance" [0.3 0.4 0.5]
)" + kQuad),
                        {});
  // Rec. 2020 → XYZ (ITU-R BT.2087) and XYZ → sRGB (IEC 61966-2-1): both D65, nothing to adapt.
  const double to_xyz[3][3] = {{0.636958, 0.144617, 0.168881},
                               {0.262700, 0.677998, 0.059302},
                               {0.000000, 0.028073, 1.060985}};
  const double to_srgb[3][3] = {{3.2406255, -1.5372080, -0.4986286},
                                {-0.9689307, 1.8757561, 0.0415175},
                                {0.0557101, -0.2040211, 1.0569959}};
  const double rgb[3] = {0.3, 0.4, 0.5};
  double xyz[3] = {0, 0, 0}, want[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) xyz[i] += to_xyz[i][j] * rgb[j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) want[i] += to_srgb[i][j] * xyz[j];
  const auto got = s.at("materials").at("rec").at("passive").at("reflectance").at("rgb");
  // The published matrices are rounded (and the two standards' D65 whites differ in the 5th
  // digit): 1e-4 is what they agree to.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i].get<double>(), want[i], 1e-4) << i;
  // AttributeEnd restores sRGB.
  EXPECT_EQ(s.at("materials").at("back").at("passive").at("reflectance").at("rgb")[0], 0.3);
  // A grey reflectance stays grey: Bradford carries ACES' D60 white to D65's.
  for (const auto& v : s.at("materials").at("aces").at("passive").at("reflectance").at("rgb"))
    EXPECT_NEAR(v.get<double>(), 0.5, 1e-6);
  // An emitter keeps its colour: Rec. 2020's white is D65's, ACES' white is D60 (x .32168,
  // y .33767), and its sRGB triple has D60's chromaticity.
  for (const auto& v : s.at("lights")[0].at("intensity").at("rgb_illuminant"))
    EXPECT_NEAR(v.get<double>(), 1, 1e-6);
  const auto d60 = s.at("lights")[1].at("intensity").at("rgb_illuminant");
  const double from_srgb[3][3] = {{0.4123908, 0.3575843, 0.1804808},
                                  {0.2126390, 0.7151687, 0.0721923},
                                  {0.0193308, 0.1191948, 0.9505322}};
  double w[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w[i] += from_srgb[i][j] * d60[j].get<double>();
  EXPECT_NEAR(w[0] / (w[0] + w[1] + w[2]), 0.32168, 1e-5);
  EXPECT_NEAR(w[1] / (w[0] + w[1] + w[2]), 0.33767, 1e-5);
  EXPECT_NEAR(w[1], 1, 1e-6);  // the RGB's luminance: ACES' (1, 1, 1) has Y = 1
}

TEST(PbrtLanguage, ColorSpaceAndFilmColorspaceNamesAreChecked) {
  const std::string h = kHeader;
  EXPECT_EQ(error_tail(h + "ColorSpace \"adobe\"\n" + kQuad),
            "blocks.pbrt:5: ColorSpace \"adobe\": unknown color space (srgb, rec2020, dci-p3, "
            "aces2065-1)");
  EXPECT_EQ(
      error_tail("Film \"rgb\" \"string colorspace\" \"xyz\"\nWorldBegin\n" + std::string(kQuad)),
      "blocks.pbrt:1: Film: unknown \"colorspace\" \"xyz\" (srgb, rec2020, dci-p3, "
      "aces2065-1)");
  EXPECT_NO_THROW(
      load_scene(write_file("film.pbrt",
                            "Film \"rgb\" \"string colorspace\" \"dci-p3\"\nColorSpace \"DCI-P3\"\n"
                            "WorldBegin\n" +
                                std::string(kQuad))));
}
