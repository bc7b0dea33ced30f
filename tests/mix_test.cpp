// Mixes (pbrt-v4's MixMaterial; docs/materials.md#mixes): one of two materials per point, the
// second with probability `amount`. In the passive furnace (an emitting sphere seen from inside,
// where every point sees the whole sphere alike) the field a mix leaves is the furnace of the
// blended material (1 − t)·A + t·B, whose radiance is analytic: every integrator must find it.
// A mix of a fluorescent material tests that the camera and the light side see one choice per
// point (vcm's stored light vertices resolve it again); the importer reads pbrt-v4's parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/input_file.h"
#include "furnace_scene.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "scene/pbrt/pbrt_import.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// Two Lambert reflectances and their blend at t = 0.3, in every bin.
const char* kLambertMix = R"({
  "dark": {"passive": {"reflectance": {"nm": [380, 780], "value": [0.2, 0.6]}}},
  "light": {"passive": {"reflectance": {"nm": [380, 780], "value": [0.9, 0.3]}}},
  "wall": {"mix": {"materials": ["dark", "light"], "amount": 0.3}},
  "blend": {"passive": {"reflectance": {"nm": [380, 780], "value": [0.41, 0.51]}}}})";

TEST(Mix, ParsedResolvedAndRefused) {
  const Scene s = load_scene(write_file("mix_parse.json", furnace_scene(kLambertMix, "wall")));
  const Material& wall = s.materials.at(s.material_index("wall"));
  ASSERT_TRUE(wall.mix.has_value());
  EXPECT_EQ(wall.kind, MaterialKind::mix);
  EXPECT_EQ(wall.mix->materials[0], s.material_index("dark"));
  EXPECT_EQ(wall.mix->materials[1], s.material_index("light"));
  EXPECT_DOUBLE_EQ(wall.mix->amount, 0.3);
  EXPECT_TRUE(s.mixed());
  const auto refused = [](const std::string& materials, const std::string& textures = "{}") {
    return error_of([&] {
      load_scene(write_file("mix_bad.json", furnace_scene(materials, "m", std::nullopt, textures)));
    });
  };
  const std::string lambert = R"("a": {"passive": {"reflectance": 0.5}})";
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a", "b"]}}})")
                .find("no material named \"b\""),
            std::string::npos);
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a"]}}})")
                .find("expected two material names"),
            std::string::npos);
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a", "a"], "amount": 1.5}}})")
                .find("/materials/m/mix/amount"),
            std::string::npos);
  EXPECT_NE(refused("{" + lambert +
                    R"(, "m": {"mix": {"materials": ["a", "a"]}, "passive": {"reflectance": 1}}})")
                .find("no \"passive\" part of its own"),
            std::string::npos);
  // A mix that names itself in turn, and a texture that is no scene texture.
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a", "n"]}},
                                         "n": {"mix": {"materials": ["m", "a"]}}})")
                .find("mixes nest deeper than 8"),
            std::string::npos);
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a", "a"], "amount": "t"}}})")
                .find("no texture named \"t\""),
            std::string::npos);
  EXPECT_NE(refused("{" + lambert + R"(, "m": {"mix": {"materials": ["a", "a"], "amount": "t"}}})",
                    R"({"t": {"type": "checkerboard", "even": 0.5, "odd": 2}})")
                .find("numbers in [0, 1]"),
            std::string::npos);
}

// KASHA_MIX only where a shape's material is a mix; a mix's materials switch on what they need.
TEST(Mix, KernelsCarryItOnlyWhereASceneUsesIt) {
  const std::string materials = R"({"plain": {"passive": {"reflectance": 0.5}},
    "ink": {"fluorescence": {"excitation": 0.3, "emission": {"gaussian_nm": 540, "fwhm_nm": 40}}},
    "m": {"mix": {"materials": ["plain", "ink"]}}})";
  CommandResult mixed =
      run_kasha("info " + write_file("mix_info.json", furnace_scene(materials, "m")));
  ASSERT_EQ(mixed.exit_code, 0) << mixed.err;
  EXPECT_NE(mixed.out.find("-D KASHA_MIX=1"), std::string::npos) << mixed.out;
  EXPECT_NE(mixed.out.find("-D KASHA_FLUORESCENCE=1"), std::string::npos) << mixed.out;
  CommandResult plain =
      run_kasha("info " + write_file("mix_plain.json", furnace_scene(materials, "plain")));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("-D KASHA_MIX=0"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("-D KASHA_FLUORESCENCE=0"), std::string::npos) << plain.out;
}

class MixFurnace : public ::testing::TestWithParam<std::string> {};

// A wall that is dark at 70 % of its points and light at 30 % is the furnace of the blend.
TEST_P(MixFurnace, LambertMixIsTheFurnaceOfTheBlend) {
  const std::vector<double> truth = furnace_radiance(furnace_scene(kLambertMix, "blend"));
  // Either material alone is far from it: the test sees a mix that is not resolved.
  const std::vector<double> dark = furnace_radiance(furnace_scene(kLambertMix, "dark"));
  EXPECT_GT(std::abs(dark[0] / truth[0] - 1), 0.2);
  expect_furnace_render(GetParam(), furnace_scene(kLambertMix, "wall"), truth);
}

INSTANTIATE_TEST_SUITE_P(Registry, MixFurnace, ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

// A fluorescent material mixed at t = 0.4 (a constant, then a texture of that value): the
// furnace of passive 0.6·0.5 + 0.4·0.3 and excitation 0.4·a. vcm connects camera vertices to
// light vertices stored on the mix, so its surface there must be the one the light path chose.
TEST(Mix, FluorescentMixAgreesFromBothEnds) {
  const std::string ink =
      R"("fluorescence": {"excitation": {"nm": [380, 450, 520], "value": [0.5, 0.4, 0]},
                         "emission": {"gaussian_nm": 560, "fwhm_nm": 40}})";
  const std::string materials = R"({"plain": {"passive": {"reflectance": 0.5}},
    "ink": {"passive": {"reflectance": 0.3}, )" +
                                ink + R"(},
    "m": {"mix": {"materials": ["plain", "ink"], "amount": 0.4}},
    "mt": {"mix": {"materials": ["plain", "ink"], "amount": "t"}}})";
  const std::string blend = R"({"b": {"passive": {"reflectance": 0.42},
    "fluorescence": {"excitation": {"nm": [380, 450, 520], "value": [0.2, 0.16, 0]},
                     "emission": {"gaussian_nm": 560, "fwhm_nm": 40}}}})";
  const std::string texture = R"({"t": {"type": "checkerboard", "even": 0.4, "odd": 0.4}})";
  RenderSettings s;
  s.grid = kFurnaceGrid;
  const std::vector<double> truth = furnace_radiance(furnace_scene(blend, "b"));
  s.integrator_settings.spp = 8;
  s.integrator_settings.photons = 1 << 13;
  s.passes = 12;
  for (const char* wall : {"m", "mt"})
    for (const char* integrator : {"backward", "vcm"}) {
      s.integrator = integrator;
      RenderResult r =
          render_scene(write_file(std::string("mix_ink_") + wall + ".json",
                                  furnace_scene(materials, wall, std::nullopt, texture)),
                       s);
      EXPECT_EQ(r.scene.textured(), std::string(wall) == "mt");
      expect_bins_match(r, truth, 0.02, std::string(integrator) + " " + wall, true);
    }
}

// A mirror mixed with a Lambert material: a light subpath stores a vertex only where it met the
// Lambert one, and bpt's connection there evaluates the surface again: were its choice not the
// light path's, half of them would meet the mirror, which connects nothing, and bpt would fall
// short of the furnace of passive 0.5·0.5 and mirror 0.5·0.9. (Merges gather photons stored at
// other points, which a mirror's share thins: docs/materials.md#mixes.)
TEST(Mix, MirrorMixConnectsWhereTheLightPathChoseLambert) {
  const std::string materials = R"({"matte": {"passive": {"reflectance": 0.5}},
    "mirror": {"gloss": {"reflectance": 0.9, "mirror": true}},
    "m": {"mix": {"materials": ["matte", "mirror"]}},
    "b": {"passive": {"reflectance": 0.25}, "gloss": {"reflectance": 0.45, "mirror": true}}})";
  RenderSettings s;
  s.grid = GridRequest{380, 780, 40};
  const std::vector<double> truth = furnace_radiance(furnace_scene(materials, "b"), *s.grid);
  s.integrator_settings.spp = 8;
  s.passes = 12;
  for (const char* integrator : {"backward", "bpt"}) {
    s.integrator = integrator;
    RenderResult r = render_scene(write_file("mix_mirror.json", furnace_scene(materials, "m")), s);
    expect_bins_match(r, truth, 0.02, integrator, true);
  }
}

// The merging integrators fall short on a mix with a mirror (above): `render` says so once with
// them, not with the unbiased ones, and not for a mix of two scattering materials.
TEST(Mix, MergingOnAMirrorMixIsWarnedAbout) {
  const std::string materials = R"({"matte": {"passive": {"reflectance": 0.5}},
    "mirror": {"gloss": {"reflectance": 0.9, "mirror": true}},
    "m": {"mix": {"materials": ["matte", "mirror"]}}})";
  const std::string mirror_mix = write_file("mix_warn.json", furnace_scene(materials, "m"));
  EXPECT_TRUE(load_scene(mirror_mix).mixes_delta());
  EXPECT_FALSE(
      load_scene(write_file("mix_nowarn.json", furnace_scene(kLambertMix, "wall"))).mixes_delta());
  const std::string warning = "a mix with a smooth (delta) material";
  for (const char* integrator : {"vcm", "photon", "backward", "bpt"}) {
    const CommandResult r =
        run_kasha("render " + shell_quoted(mirror_mix) + " --integrator " + integrator +
                  " --passes 1 --spp 1 -o " + shell_quoted(mirror_mix + ".exr"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const bool merges = std::string(integrator) == "vcm" || std::string(integrator) == "photon";
    EXPECT_EQ(r.err.find(warning) != std::string::npos, merges) << integrator << ": " << r.err;
  }
}

// scenes/cornell_box.json with its floor a mix of white and a glossy material and its red wall a
// mix of red and the fluorescent Post-it, in tmp: its files' paths made absolute.
std::string mixed_cornell_box() {
  nlohmann::json d = nlohmann::json::parse(
      read_input_file(source_path("scenes/cornell_box.json"), kMaxTextInputBytes));
  std::function<void(nlohmann::json&)> absolute = [&](nlohmann::json& j) {
    for (auto& [key, value] : j.items()) {
      if ((key == "csv" || key == "file") && value.is_string())
        value = source_path("scenes/" + value.get<std::string>());
      else if (value.is_structured())
        absolute(value);
    }
  };
  absolute(d);
  d["materials"]["shiny"] = nlohmann::json::parse(
      R"({"passive": {"reflectance": 0.3}, "gloss": {"reflectance": 0.5, "cone_deg": 20}})");
  d["materials"]["floor"] = {{"mix", {{"materials", {"white", "shiny"}}, {"amount", 0.5}}}};
  d["materials"]["wall"] = {{"mix", {{"materials", {"red", "postit"}}, {"amount", 0.6}}}};
  for (auto& shape : d["shapes"]) {
    if (shape["material"] == "red") shape["material"] = "wall";
  }
  d["shapes"][0]["material"] = "floor";
  return write_file("mixed_cornell_box.json", d.dump());
}

// vcm's connections evaluate the surface at light vertices stored on the mixes, its merges the
// camera vertex's: the mixed regions agree with backward within noise (and 2 %).
TEST(Mix, GlossyAndFluorescentMixesAgreeWithBackward) {
  const std::string path = mixed_cornell_box();
  Camera cam = load_scene(path).camera;
  cam.width = cam.height = 32;
  RenderSettings s;
  s.camera = cam;
  s.spectral = false;
  s.passes = 8;
  s.integrator_settings.spp = 64;
  const RenderResult backward = render_scene(path, s);
  s.integrator = "vcm";
  s.passes = 12;
  s.integrator_settings.spp = 4;
  s.integrator_settings.photons = 1 << 17;
  const RenderResult vcm = render_scene(path, s);
  const auto regions = primary_hit_regions(vcm.scene, cam);
  for (const char* name : {"floor", "wall"}) {
    ASSERT_TRUE(regions.count(name)) << name;
    const std::vector<size_t>& pixels = regions.at(name);
    BinStats t = pixel_statistics(vcm.image, false, pixels);
    BinStats d = difference_statistics(vcm.image, backward.image, false, pixels);
    for (int k = 0; k < 3; ++k) {
      const double b = t.mean[k] - d.mean[k];
      std::printf("  %s row %d: vcm/backward - 1 = %+.2f %% (%.1f standard errors)\n", name, k,
                  100 * d.mean[k] / b, d.mean[k] / d.standard_error[k]);
      EXPECT_LT(std::abs(d.mean[k]), 0.02 * b) << name << " row " << k;
      EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << name << " row " << k;
    }
  }
}

// pbrt-v4's Material "mix": "string materials" two named materials, "float amount" 0.5.
const char* kHead =
    "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";
const char* kQuad =
    "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
    "\"integer indices\" [0 1 2  0 2 3]\n";

nlohmann::json imported(const std::string& body) {
  return import_pbrt_scene(write_file("mix.pbrt", std::string(kHead) + body + kQuad), {});
}

// The line "FILE:LINE: …" of the error `body` gives, one line.
std::string refusal(const std::string& body) {
  const std::string e =
      error_of([&] { load_scene(write_file("mixbad.pbrt", std::string(kHead) + body + kQuad)); });
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const size_t at = e.find("mixbad.pbrt");
  return at == std::string::npos ? e : e.substr(at);
}

TEST(Mix, PbrtParametersAndDefaultsAsPbrtV4) {
  const std::string two = R"(MakeNamedMaterial "a" "string type" "diffuse"
MakeNamedMaterial "b" "string type" "conductor"
)";
  nlohmann::json s =
      imported(two + R"(MakeNamedMaterial "m" "string type" "mix" "string materials" ["a" "b"]
MakeNamedMaterial "over" "string type" "mix" "string materials" ["m" "a"] "float amount" 1.7
Material "mix" "string materials" ["later" "over"] "float amount" -1
MakeNamedMaterial "later" "string type" "diffuse"
)");
  const nlohmann::json& m = s.at("materials");
  EXPECT_EQ(m.at("m").at("mix"),
            nlohmann::json::parse(R"({"materials": ["a", "b"], "amount": 0.5})"));
  EXPECT_EQ(m.at("over").at("mix").at("amount"), 1.0);  // ChooseMaterial: ≥ 1 is the second
  // An anonymous mix may name a named material defined after it (pbrt-v4 makes those first).
  const std::string anonymous = "pbrt material at " + write_file("mix.pbrt", "") + ":9";
  ASSERT_TRUE(m.contains(anonymous)) << m.dump();
  EXPECT_EQ(m.at(anonymous).at("mix").at("amount"), 0.0);
  // A float texture: a constant gives its value, a varying one is the amount's kasha texture.
  s = imported(two + R"(Texture "half" "float" "constant" "float value" 0.25
Texture "checks" "float" "checkerboard" "float tex1" 0.2 "float tex2" 0.9
MakeNamedMaterial "c" "string type" "mix" "string materials" ["a" "b"] "texture amount" "half"
MakeNamedMaterial "v" "string type" "mix" "string materials" ["a" "b"] "texture amount" "checks"
NamedMaterial "v"
)");
  EXPECT_EQ(s.at("materials").at("c").at("mix").at("amount"), 0.25);
  const std::string checks = s.at("materials").at("v").at("mix").at("amount");
  ASSERT_TRUE(s.at("textures").contains(checks)) << s.dump();
  EXPECT_EQ(s.at("textures").at(checks).at("odd"), 0.9);
  const Scene loaded = load_scene(write_file("mixv.pbrt", std::string(kHead) + two + R"(
Texture "checks" "float" "checkerboard" "float tex1" 0.2 "float tex2" 0.9
MakeNamedMaterial "v" "string type" "mix" "string materials" ["a" "b"] "texture amount" "checks"
NamedMaterial "v"
)" + kQuad));
  EXPECT_TRUE(loaded.mixed());
  EXPECT_TRUE(loaded.textured());
  EXPECT_TRUE(loaded.uses(MaterialKind::conductor));
}

TEST(Mix, PbrtRefusalsAreOneLineWithTheirPlace) {
  const std::string a = "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n";
  EXPECT_EQ(refusal(a + R"(Material "mix" "string materials" ["a"])" + "\n"),
            "mixbad.pbrt:6: mix: \"string materials\" must name two materials");
  EXPECT_EQ(refusal(a + R"(Material "mix" "string materials" ["a" "ghost"])" + "\n"),
            "mixbad.pbrt:6: mix: no named material \"ghost\" defined before it");
  // A named mix names only what is defined before it, as pbrt-v4 creates them in order.
  EXPECT_EQ(refusal(a + R"(MakeNamedMaterial "m" "string type" "mix" "string materials" ["a" "z"]
MakeNamedMaterial "z" "string type" "diffuse"
)"),
            "mixbad.pbrt:6: mix: no named material \"z\" defined before it");
  EXPECT_EQ(refusal(a + R"(MakeNamedMaterial "i" "string type" "interface"
Material "mix" "string materials" ["a" "i"]
)"),
            "mixbad.pbrt:7: mix: \"i\" is an \"interface\" material, which a mix cannot hold");
  // The command line says it in one line too.
  CommandResult r = run_kasha(
      "info " +
      write_file("mixcli.pbrt", std::string(kHead) + a +
                                    "Material \"mix\" \"string materials\" [\"a\"]\n" + kQuad));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "kasha: error: " + write_file("mixcli.pbrt", "") +
                       ":6: mix: \"string materials\" must name two materials\n");
}

}  // namespace
