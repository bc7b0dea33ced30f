// Participating media (docs/media.md): homogeneous absorbing media bounded by shapes' medium
// interfaces, "interface" shapes that only bound them, and the camera inside one. An emitter seen
// through a slab of dye against Beer–Lambert per bin in every integrator (the absorption varies
// across the bins, so a grey or single-bin mistake shows), a dye inside a glass sphere against
// backward in every integrator, and the scene and pbrt-v4 readers' acceptance and refusals.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "scene/colour_grid.h"
#include "scene/medium_light_region.h"
#include "scene/pbrt/pbrt_import.h"
#include "scene/scene.h"
#include "spectrum/rgb_spectrum.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// A lamp quad at z = 0 facing +z, seen along −z by an orthographic camera (every ray's path the
// same length) from z = 3 through a slab of "dye" (z in
// [0.5, 1.5]) bounded by an interface box; the camera, and the space outside the slab, in "haze".
std::string slab_scene() {
  return R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "type": "orthographic", "width": 8,
               "height": 8, "medium": "haze"},
    "media": {"dye": {"sigma_a": {"nm": [380, 780], "value": [2.0, 0.2]}, "sigma_s": 0},
              "haze": {"sigma_a": 0.1, "sigma_s": 0}},
    "materials": {"black": {}},
    "shapes": [
      {"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "black",
       "emission": 0.01, "medium": {"inside": null, "outside": "haze"}},
      {"type": "box", "min": [-2, -2, 0.5], "max": [2, 2, 1.5], "interface": true,
       "medium": {"inside": "dye", "outside": "haze"}}]})";
}

class MediumSlab : public ::testing::TestWithParam<std::string> {};

// 2 units of haze and 1 of dye: L·exp(−2 σ_haze − σ_dye) in every bin.
TEST_P(MediumSlab, AnEmitterSeenThroughASlabOfDyeFollowsBeerLambertPerBin) {
  const std::string path = write_file("medium_slab.json", slab_scene());
  RenderSettings s;
  s.integrator = GetParam();
  s.grid = GridRequest{380, 780, 20};
  s.integrator_settings.spp = 16;
  s.integrator_settings.photons = 1 << 16;
  s.passes = 4;
  RenderResult r = render_scene(path, s);
  ASSERT_EQ(r.scene.media.size(), 2u);
  const Medium& dye = r.scene.media[0];
  std::vector<double> truth = r.scene.emitters.at(0).per_bin;
  ASSERT_GT(dye.sigma_a.front() / dye.sigma_a.back(), 5.0);
  for (size_t i = 0; i < truth.size(); ++i) truth[i] *= std::exp(-dye.sigma_a[i] - 2 * 0.1);
  // Each crossing starts the next piece of the ray off the surface (about 10⁻⁵ here), so the
  // lengths are short by that much: a bias of 2·10⁻⁵, above the noise of the integrators that see
  // the lamp along camera paths; the check is the tolerance, 0.2 % (light tracing's noise: 2 %).
  expect_bins_match(r, truth, GetParam() == "forward" ? 0.02 : 0.002, GetParam() + " through the slab", false);
}

INSTANTIATE_TEST_SUITE_P(Registry, MediumSlab, ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

// scenes/dye_in_glass.json, a glass sphere of dye on a white floor under a lamp: the light through
// the dye (refracted, attenuated, caustics on the floor) in every integrator against backward's.
TEST(Medium, EveryIntegratorAgreesWithBackwardOnDyeInGlass) {
  for (const std::string integrator : {"forward", "photon", "vcm", "bpt", "ppm"}) {
    ComparedRenders c = render_against_backward("dye_in_glass.json", integrator, 8, 1 << 16, 32);
    // The floor (its shadow and caustic through the dye); light tracing cannot see the glass.
    const std::vector<size_t> floor = primary_hit_regions(c.tested.scene, c.camera).at("white");
    const std::vector<size_t> all = integrator == "forward" ? floor : std::vector<size_t>{};
    const BinStats a = pixel_statistics(c.tested.image, false, all),
                   b = pixel_statistics(c.backward.image, false, all);
    for (int row = 0; row < 3; ++row)
      EXPECT_NEAR(a.mean[row] / b.mean[row], 1.0, 0.03) << integrator << " row " << row;
  }
}

// scenes/tonic_under_uv_spot.json, quinine in water lit by a 365 nm spot: the light the camera
// sees is the dye's blue re-emission from the beam and what it lights around. Light tracing and
// photon mapping (collisions splatted; photons stored at collisions, gathered in 3-D) against
// backward's, over the image and the floor, at 32 × 24. Backward's floor is lit by the glowing
// beam through paths that find it by chance, so its reference takes 8192 samples a pixel (its
// means vary by 3 % between seeds at 1024); photon mapping's 64 passes let its radii shrink past
// their first passes' blur (−7 % after 16).
TEST(Medium, ForwardPhotonAndVcmAgreeWithBackwardOnTonicWaterUnderAUvSpot) {
  const std::string path = source_path("scenes/tonic_under_uv_spot.json");
  RenderSettings s;
  s.camera = load_scene(path).camera;
  s.camera->width = 32;
  s.camera->height = 24;
  s.spectral = false;
  s.integrator = "backward";
  s.integrator_settings.spp = 256;
  s.passes = 32;
  const RenderResult backward = render_scene(path, s);
  const std::vector<size_t> floor = primary_hit_regions(backward.scene, *s.camera).at("white");
  // vcm: collisions connected and merged (one light subpath a pixel times 8, its default here).
  for (const std::string integrator : {"forward", "photon", "vcm"}) {
    s.integrator = integrator;
    s.integrator_settings.photons = integrator == "vcm" ? 32 * 24 * 8 : 1 << 16;
    s.integrator_settings.spp = integrator == "vcm" ? 16 : 256;
    s.passes = integrator == "photon" ? 64 : integrator == "vcm" ? 32 : 16;
    const RenderResult tested = render_scene(path, s);
    ASSERT_TRUE(tested.scene.scattering());
    for (const std::vector<size_t>& pixels : {std::vector<size_t>{}, floor}) {
      const BinStats a = pixel_statistics(tested.image, false, pixels),
                     b = pixel_statistics(backward.image, false, pixels);
      for (int row = 0; row < 3; ++row)
        EXPECT_NEAR(a.mean[row] / b.mean[row], 1.0, 0.04)
            << integrator << (pixels.empty() ? " image" : " floor") << " row " << row;
    }
  }
}

// The glass alone (no dye) is brighter in every row, the blue row most: the dye does something.
TEST(Medium, TheDyeAbsorbsMoreWhereItsSigmaIsHigher) {
  const std::string base = R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 1, "width": 4, "height": 4},
    "wavelengths": {"min_nm": 380, "max_nm": 780, "bin_nm": 20},
    "media": {"dye": {"sigma_a": {"nm": [380, 780], "value": [3.0, 0.0]}, "sigma_s": 0}},
    "materials": {"black": {}, "glass": {"dielectric": {"eta": 1.5}}},
    "shapes": [
      {"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "black",
       "emission": 0.01},
      {"type": "sphere", "center": [0, 0, 1], "radius": 0.5, "material": "glass"MEDIUM}]})";
  RenderSettings s;
  s.passes = 2;
  s.integrator_settings.spp = 16;
  const auto with = [&](const std::string& medium) {
    std::string text = base;
    text.replace(text.find("MEDIUM"), 6, medium);
    return render_scene(write_file("medium_dye_or_not.json", text), s);
  };
  const RenderResult clear = with(""), dyed = with(R"(, "medium": {"inside": "dye"})");
  const BinStats a = pixel_statistics(clear.image, true), b = pixel_statistics(dyed.image, true);
  const size_t n = a.mean.size();
  // Through the sphere's centre: 1 unit of dye; σ falls from 3 to 0 across the bins.
  EXPECT_NEAR(b.mean.front() / a.mean.front(), std::exp(-dyed.scene.media[0].sigma_a.front()), 0.01);
  EXPECT_NEAR(b.mean.back() / a.mean.back(), std::exp(-dyed.scene.media[0].sigma_a.back()), 0.01);
  EXPECT_LT(b.mean[n / 2] / a.mean[n / 2], 0.5);
}

TEST(Medium, BadMediaAreOneLine) {
  struct Case {
    std::string media, shape, message;
  };
  const std::string quad = R"({"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], )";
  const std::vector<Case> cases = {
      {R"("fog": {"sigma_a": -1})", R"("material": "m"})", "/media/fog/sigma_a: negative spectrum value"},
      {R"("fog": {"g": 1})", R"("material": "m"})", "/media/fog/g: the phase function's g must lie"},
      {R"("fog": {"type": "uniformgrid"})", R"("material": "m"})", "/media/fog/type: unknown medium type"},
      {R"("fog": {"sigma_s": 0, "scale": -2})", R"("material": "m"})", "/media/fog/scale"},
      {R"("fog": {"sigma_s": 0})", R"("material": "m", "medium": {"inside": "smoke"}})",
       "/shapes/0/medium/inside: no medium named \"smoke\""},
      {R"("fog": {"sigma_s": 0})", R"("interface": true})", "/shapes/0/interface: an interface bounds media"},
      {R"("fog": {"sigma_s": 0})", R"("interface": true, "material": "m", "medium": {"inside": "fog"}})",
       "/shapes/0/interface: an interface has no material"},
  };
  for (const Case& c : cases) {
    const std::string text = R"({"kasha_scene": 1, "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
      "materials": {"m": {}}, "media": {)" + c.media + R"(}, "shapes": [)" + quad + c.shape + "]}";
    const std::string file = write_file("bad_medium.json", text);
    const std::string e = error_of([&] { load_scene(file); });
    EXPECT_NE(e.find(c.message), std::string::npos) << c.media << " " << c.shape << "\n  got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  // A medium nothing is in is read and left alone.
  const std::string unused = write_file("unused_medium.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]}, "materials": {"m": {}},
    "media": {"fog": {"sigma_s": 1}}, "shapes": [)" + quad + R"("material": "m"}]})");
  EXPECT_FALSE(load_scene(unused).has_media());
  EXPECT_FALSE(load_scene(unused).scattering());
}

// pbrt-v4's MakeNamedMedium "homogeneous", MediumInterface, the "interface" material, the camera's
// and a point light's outside medium, as kasha's scene.
TEST(Medium, PbrtMediaImportAsKashas) {
  const nlohmann::json s = import_pbrt_scene(write_file("media.pbrt", R"(
LookAt 0 1 3  0 0 0  0 1 0
MediumInterface "" "air"
Camera "perspective"
WorldBegin
MakeNamedMedium "air" "string type" "homogeneous" "rgb sigma_a" [0.01 0.01 0.01] "rgb sigma_s" [0 0 0]
MakeNamedMedium "tea" "string type" "homogeneous" "rgb sigma_a" [0.1486 0.321 0.736] "float sigma_s" 0 "float scale" 2
LightSource "point" "point3 from" [0 2 0]
AttributeBegin
  MediumInterface "tea" "air"
  Material "dielectric" "float eta" 1.33
  Shape "sphere"
AttributeEnd
AttributeBegin
  MediumInterface "tea" "air"
  Material "interface"
  Translate 3 0 0
  Shape "sphere"
AttributeEnd
AttributeBegin
  MediumInterface "air" "air"
  Material "interface"
  Shape "sphere" "float radius" 2
AttributeEnd
)"),
                                               {});
  EXPECT_EQ(s.at("camera").at("medium"), "air");
  EXPECT_EQ(s.at("lights").at(0).at("medium"), "air");
  EXPECT_EQ(s.at("media").at("tea").at("scale"), 2.0);
  EXPECT_EQ(s.at("media").at("tea").at("sigma_s"), 0.0);
  ASSERT_EQ(s.at("shapes").size(), 2u);  // the interface between air and air bounds nothing
  EXPECT_EQ(s.at("shapes").at(0).at("medium"), nlohmann::json::parse(R"({"inside": "tea", "outside": "air"})"));
  EXPECT_TRUE(s.at("shapes").at(1).at("interface").get<bool>());
  EXPECT_FALSE(s.at("shapes").at(1).contains("material"));
}

// A furnace of scattering media: a ball of a medium that scatters and does not absorb inside a black
// sphere that emits L inwards, the camera between them. Light is neither lost nor made inside, so the
// radiance is L everywhere, in every bin, whatever σs(λ) and g — the whole of multiple scattering,
// the free flight's MIS over bins (σs spans a factor 8 here), next-event estimation from medium
// vertices and its MIS against the phase function's sampling, in one number.
// Inside a black sphere of radius 1 emitting 0.01 inwards, a ball of radius 0.7 of the medium
// "fill" (its JSON entry) and the camera in the gap, looking at the ball from 0.15 off it; the
// furnaces' scene. The camera stays out of the medium: light tracing's splats from collisions
// next to a camera inside one, 1/d², have infinite variance (docs/media.md).
std::string sphere_furnace(const std::string& fill) {
  return R"({"kasha_scene": 1,
    "camera": {"position": [0.1, 0, 0.85], "look_at": [0, 0, 0], "fov_deg": 60, "width": 8, "height": 8},
    "wavelengths": {"min_nm": 380, "max_nm": 780, "bin_nm": 40},
    "media": {"fill": )" + fill + R"(},
    "materials": {"black": {}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "segments": 32, "inward": true,
                "material": "black", "emission": 0.01},
               {"type": "sphere", "center": [0, 0, 0], "radius": 0.7, "segments": 32, "interface": true,
                "medium": {"inside": "fill"}}]})";
}

std::string scattering_furnace(double g) {
  return sphere_furnace(R"({"sigma_a": 0, "sigma_s": {"nm": [380, 780], "value": [4.0, 0.5]}, "g": )" +
                        std::to_string(g) + "}");
}

// A render of a furnace scene: backward's 4 passes of 64 samples a pixel, light tracing's 4 of
// 2^17 photons, photon mapping's 32 of 2^16, or vcm's, bpt's and ppm's 16 of 64 camera paths a
// pixel and 2^12 light subpaths.
RenderResult render_furnace(const std::string& name, const std::string& scene,
                            const std::string& integrator = "backward") {
  RenderSettings s;
  const bool vcm_family = integrator == "vcm" || integrator == "bpt" || integrator == "ppm";
  s.integrator = integrator;
  s.integrator_settings.spp = 64;
  s.integrator_settings.photons = integrator == "photon" ? 1 << 16 : vcm_family ? 1 << 12 : 1 << 17;
  s.passes = integrator == "photon" ? 32 : vcm_family ? 16 : 4;
  return render_scene(write_file(name, scene), s);
}

TEST(Medium, AScatteringFurnaceShowsTheEmittersRadianceInEveryBin) {
  for (double g : {0.0, 0.7, -0.4}) {
    RenderResult r = render_furnace("scattering_furnace.json", scattering_furnace(g));
    ASSERT_TRUE(r.scene.scattering());
    expect_bins_match(r, r.scene.emitters.at(0).per_bin, 0.02, "furnace g " + std::to_string(g));
  }
  // Light tracing: each collision splatted to the camera through the phase function; photon
  // mapping: photons stored at collisions, gathered in 3-D at the camera paths' collisions
  // through the phase function; vcm, bpt and ppm: collisions as vertices of every technique.
  for (const std::string integrator : {"forward", "photon", "vcm", "bpt", "ppm"}) {
    RenderResult p = render_furnace("scattering_furnace.json", scattering_furnace(0.7), integrator);
    expect_bins_match(p, p.scene.emitters.at(0).per_bin, 0.05, integrator + " furnace g 0.7");
  }
}

// A fluorescent furnace: the same sphere filled with a dye that re-emits all it absorbs (Φ = 1)
// in the shape of its own absorption, and scatters a little. Where the light is flat, absorption
// in each bin σ_i L is balanced by re-emission ê_i Σ_j σ_j L, so the radiance stays L in every
// bin — while every path that re-emits turns rank-1 and moves its energy across the bins, through
// the collision's branch choice, the fluorescent next-event estimate and its MIS.
// Two dyes of opposite slopes balance the same way, each on its own; their branches are chosen
// by their energies, which the furnace checks as well.
TEST(Medium, AFluorescentFurnaceWhoseDyeReemitsItsAbsorptionShowsTheEmittersRadiance) {
  const std::string absorption = R"({"nm": [380, 780], "value": [3.0, 0.2]})",
                    second = R"({"nm": [380, 780], "value": [0.1, 1.5]})";
  const std::string scene = sphere_furnace(R"({"sigma_a": 0, "sigma_s": 0.3, "g": 0.5,
      "fluorophores": [{"absorption": )" + absorption + R"(, "quantum_yield": 1, "emission": )" +
                                           absorption + R"(},
                       {"absorption": )" + second + R"(, "quantum_yield": 1, "emission": )" + second +
                                           "}]}");
  const std::vector<double> emitter = load_scene(write_file("fluorescent_furnace.json", scene)).emitters.at(0).per_bin;
  for (const std::string integrator : {"backward", "forward", "photon", "vcm", "bpt", "ppm"}) {
    RenderResult r = render_furnace("fluorescent_furnace.json", scene, integrator);
    ASSERT_TRUE(r.scene.fluorescent());
    expect_bins_match(r, emitter, integrator == "backward" ? 0.02 : 0.05, integrator + " fluorescent furnace");
  }
  // Half the yield, and the dye's bins darken: the furnace can fail.
  std::string dim = scene;
  dim.replace(dim.find("\"quantum_yield\": 1"), 18, "\"quantum_yield\": 0.5");
  RenderResult d = render_furnace("fluorescent_furnace_dim.json", dim);
  const BinStats b = pixel_statistics(d.image, true);
  EXPECT_LT(b.mean.front(), 0.8 * emitter.front());
}

// An emitting furnace: the sphere filled with a medium that absorbs (σa varying over the bins),
// scatters and emits σa·Le with Le the enclosure's radiance L. In equilibrium what it absorbs it
// emits, so the radiance stays L everywhere, in every bin and every integrator: backward's, vcm's
// and bpt's camera paths take the emission where they collide; forward's, photon mapping's and
// ppm's light paths also start in the medium (without them photon mapping was 13–29 % low).
// Without the emission backward falls to 0.05–0.62 L. A medium that emits outside every shape
// has no box for light paths to start in: those three refuse it in one line.
TEST(Medium, AnEmittingFurnaceShowsTheEmittersRadianceInEveryIntegrator) {
  const std::string fill = R"({"sigma_a": {"nm": [380, 780], "value": [3.0, 0.3]},
      "sigma_s": {"nm": [380, 780], "value": [0.5, 2.0]}, "g": 0.5, "emission": 0.01})";
  const std::string scene = sphere_furnace(fill);
  for (const std::string integrator : {"backward", "vcm", "bpt", "forward", "photon", "ppm"}) {
    RenderResult r = render_furnace("emitting_furnace.json", scene, integrator);
    ASSERT_GE(r.scene.emitting_medium(), 0);
    expect_bins_match(r, r.scene.emitters.at(0).per_bin, integrator == "backward" ? 0.02 : 0.05,
                      integrator + " emitting furnace");
  }
  std::string outside = scene;
  outside.replace(outside.find(R"("inside": "fill")"), 16, R"("outside": "fill")");
  outside.replace(outside.find(R"("width": 8)"), 0, R"("medium": "fill", )");
  for (const std::string integrator : {"forward", "photon", "ppm"}) {
    const std::string e =
        error_of([&] { render_furnace("emitting_outside.json", outside, integrator); });
    EXPECT_NE(e.find("/media/fill: the medium emits and fills the space outside every shape"),
              std::string::npos)
        << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

// The medium past every boundary (where light paths that start in a grid's box outside every
// shape are): the side of the first boundary a ray from outside meets — a box holding fog has
// vacuum outside, turned or not; a glass box in a world of fog has fog; an inward box (its fronts
// facing in, its "inside" the world beyond), whose side faces run along x where the farthest
// vertex is, has its "inside" outside; without boundaries, the camera's medium.
TEST(Medium, TheOuterMediumIsTheSideARayFromOutsideMeetsFirst) {
  const auto outer = [](const std::string& box, const std::string& camera_medium) {
    const std::string text = R"({"kasha_scene": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0])" +
                             camera_medium + R"(}, "materials": {"m": {}}, "media": {"fog": {"sigma_s": 0}},
      "shapes": [)" + box + R"(, {"type": "quad", "corner": [-1, -1, -3], "u": [2, 0, 0], "v": [0, 2, 0],
                  "material": "m", "emission": 1}]})";
    return outer_medium(load_scene(write_file("outer_medium.json", text)));
  };
  const std::string box = R"({"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "interface": true, )";
  EXPECT_EQ(outer(box + R"("medium": {"inside": "fog"}})", ""), -1);
  EXPECT_EQ(outer(box + R"("medium": {"inside": "fog"}, "transform": {"rotate": {"axis": [0, 1, 1], "deg": 30}}})", ""), -1);
  EXPECT_EQ(outer(box + R"("medium": {"outside": "fog"}})", R"(, "medium": "fog")"), 0);
  EXPECT_EQ(outer(box + R"("medium": {"inside": "fog"}, "inward": true})", R"(, "medium": "fog")"), 0);
  EXPECT_EQ(outer(R"({"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "m"})",
                  R"(, "medium": "fog")"),
            0);
}

// A box of `medium` over z in [0.5, 1.5] (an interface shape) seen face on from above by an
// orthographic camera against black; a small dark emitter far behind the camera gives the scene
// the light every integrator asks for.
static std::string emitting_box_scene(const std::string& file, const std::string& medium,
                                      const std::string& top = "") {
  return write_file(file, R"({"kasha_scene": 1, )" + top + R"(
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "type": "orthographic", "width": 8, "height": 8},
    "media": {"glow": )" + medium +
                              R"(},
    "materials": {"black": {}},
    "shapes": [
      {"type": "box", "min": [-2, -2, 0.5], "max": [2, 2, 1.5], "interface": true, "medium": {"inside": "glow"}},
      {"type": "quad", "corner": [-0.1, -0.1, 9], "u": [0.2, 0, 0], "v": [0, 0.2, 0], "material": "black", "emission": 1}]})");
}

// A slab of a medium that absorbs and emits but does not scatter, seen face on by an orthographic
// camera against black: L = Le (1 − exp(−σa ∫ρ dz)) in each bin, per bin within 1 %, whatever the
// density ρ along z. Homogeneous (ρ = 1 over d = 1) in backward and vcm, vcm also with its light
// subpaths in several chunks (each replays the camera paths: the emission must count once); as a
// grid of density 0.5 (∫ρ dz = 0.5 · 0.9375: it falls to half at the box's faces) in backward,
// where σa·Le, like the flight's weights, leaves the density out. Light paths that start in the
// medium: forward (homogeneous, and the grid, where the photon's power takes the density), photon
// mapping (the grid) and ppm. At --max-depth 0 the slab shows nothing (pbrt-v4's volpath adds a
// medium's emission only below its maxdepth; forward counts a photon's start in the medium as a
// vertex alike), at 1 all of it.
TEST(Medium, AnEmittingSlabFollowsItsClosedForm) {
  const std::string homogeneous =
      R"({"sigma_a": {"nm": [380, 780], "value": [2.0, 0.1]}, "sigma_s": 0,
                       "emission": {"nm": [380, 780], "value": [0.02, 0.05]}})";
  std::string grid = homogeneous;
  grid.replace(1, 0,
               R"("type": "grid", "density": {"size": [2, 2, 4], "values": [0.5, 0.5, 0.5, 0.5,
      0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5]},
      "bounds": {"min": [-3, -3, 0.5], "max": [3, 3, 1.5]}, )");
  struct Case {
    std::string medium, integrator;
    double optical;  // ∫ρ dz through the slab
    unsigned long long memory;
    int max_depth;
  };
  const int none = IntegratorSettings::kNoDepthCap;
  const std::vector<Case> cases = {
      {homogeneous, "backward", 1, 0, none},   {homogeneous, "vcm", 1, 0, none},
      {homogeneous, "vcm", 1, 1 << 20, none},  {grid, "backward", 0.5 * 0.9375, 0, none},
      {homogeneous, "backward", 1, 0, 1},      {homogeneous, "backward", 0, 0, 0},
      {homogeneous, "forward", 1, 0, none},    {grid, "forward", 0.5 * 0.9375, 0, none},
      {grid, "photon", 0.5 * 0.9375, 0, none}, {homogeneous, "ppm", 1, 0, none},
      {homogeneous, "forward", 1, 0, 1},       {homogeneous, "forward", 0, 0, 0}};
  for (const Case& c : cases) {
    const std::string path = emitting_box_scene("emitting_slab.json", c.medium);
    RenderSettings s;
    s.integrator = c.integrator;
    s.integrator_settings.spp = 64;
    s.integrator_settings.photons = 1 << 12;
    s.integrator_settings.memory = c.memory;
    s.integrator_settings.max_depth = c.max_depth;
    s.passes = 4;
    RenderResult r = render_scene(path, s);
    const Medium& glow = r.scene.media.at(0);
    std::vector<double> expected(glow.sigma_a.size());
    for (size_t i = 0; i < expected.size(); ++i)
      expected[i] =
          glow.emission[i] / glow.sigma_a[i] * (1 - std::exp(-glow.sigma_a[i] * c.optical));
    const std::string what = c.integrator + " emitting slab, optical length " +
                             std::to_string(c.optical) + ", memory " + std::to_string(c.memory);
    if (c.optical == 0) {
      for (float v : r.image.xyz) EXPECT_EQ(v, 0.0f) << what;
    } else {
      expect_bins_match(r, expected, 0.01, what, false);
    }
  }
}

// A grid that emits a blackbody (pbrt-v4's temperature grids) seen face on against black, its
// density ρ, temperature v and emission scale e each given by 4 samples along z: in each bin
//   L = ∫ σa ρ(z) e(z) B̄(T(z)) exp(−σa ∫_z^top ρ) dz,  T = (v(z) − 10) · 100 K,
// B̄ the bin's mean of Planck's law over its peak (0 at 100 K and below), every factor
// interpolated as the grid interpolates (falling to 0 half a sample past the outer ones), here by
// the midpoint rule in 4000 steps and 20 nodes a bin; backward, vcm and forward within 1 % per bin.
TEST(Medium, AnEmittingTemperatureGridFollowsItsIntegral) {
  const std::vector<double> rho = {0.8, 0.4, 1.2, 0.6}, v = {50, 70, 90, 60}, e = {1, 0.5, 2, 1.5};
  const auto lattice = [](const std::vector<double>& z) {  // the 4 values at each (x, y) of 2 × 2
    std::string out = "{\"values\": [";
    for (int k = 0; k < 16; ++k) out += (k ? ", " : "") + std::to_string(z[k / 4]);
    return out + "]}";
  };
  const std::string medium = R"({"type": "grid", "sigma_a": {"nm": [380, 780], "value": [2.0, 0.1]},
      "sigma_s": 0, "density": {"size": [2, 2, 4], )" +
                             lattice(rho).substr(1) +
                             R"(, "bounds": {"min": [-3, -3, 0.5], "max": [3, 3, 1.5]},
      "temperature": )" + lattice(v) +
                             R"(, "temperature_offset": 10, "temperature_scale": 100,
      "emission_scale": )" + lattice(e) +
                             "}";
  // The grid's interpolation along z (samples at the centres of 4 cells over [0.5, 1.5]).
  const auto along = [](const std::vector<double>& f, double z) {
    const double q = (z - 0.5) * 4 - 0.5, k = std::floor(q);
    const auto at = [&](double i) { return i < 0 || i > 3 ? 0.0 : f[static_cast<size_t>(i)]; };
    return at(k) + (at(k + 1) - at(k)) * (q - k);
  };
  const auto planck = [](double nm, double T) {  // over its peak (Wien's b = 2.8977721e-3 m K)
    const double c2 = 1.4387769e-2, b = 2.8977721e-3, x = nm * 1e-9 * T;
    return std::pow(b / x, 5) * std::expm1(c2 / b) / std::expm1(c2 / x);
  };
  // Light tracing's photons start at the grid's points, with its density, scale and blackbody
  // there.
  for (const std::string integrator : {"backward", "vcm", "forward"}) {
    const std::string path = emitting_box_scene("emitting_grid.json", medium);
    RenderSettings settings;
    settings.integrator = integrator;
    settings.integrator_settings.spp = 64;
    settings.passes = 4;
    const RenderResult r = render_scene(path, settings);
    const WavelengthGrid& grid = r.scene.grid;
    std::vector<double> expected(grid.bins, 0.0);
    const int steps = 4000;
    for (int i = 0; i < grid.bins; ++i) {
      const double sigma = r.scene.media.at(0).sigma_a[i];
      double depth = 0;  // ∫ ρ from the top down to z
      for (int k = 0; k < steps; ++k) {
        const double z = 1.5 - (k + 0.5) / steps, dz = 1.0 / steps, d = along(rho, z);
        const double T = (along(v, z) - 10) * 100;
        double mean = 0;
        for (int n = 0; n < 20 && T > 100; ++n)
          mean += planck(grid.lo(i) + grid.bin_nm * (n + 0.5) / 20, T) / 20;
        expected[i] +=
            sigma * d * along(e, z) * mean * std::exp(-sigma * (depth + 0.5 * d * dz)) * dz;
        depth += d * dz;
      }
    }
    expect_bins_match(r, expected, 0.01, integrator + " emitting temperature grid", false);
  }
}

TEST(Medium, BadFluorophoresAreOneLine) {
  struct Case {
    std::string fluorophore, message;
  };
  const std::vector<Case> cases = {
      {R"({"absorption": 1, "quantum_yield": 1.5, "emission": 1})", "/quantum_yield"},
      {R"({"absorption": 1})", "/media/fog/fluorophores/0: missing required key \"emission\""},
      {R"({"emission": 1})", "a fluorophore needs its \"absorption\""},
      {R"({"absorption": 1, "molar_absorption": 1, "concentration": 1, "emission": 1})", "not both"},
      {R"({"absorption": 1, "emission": {"nm": [900, 1000], "value": [1, 1]}})", "no emission on the wavelength grid"},
      {R"({"absorption": -1, "emission": 1})", "negative spectrum value"},
  };
  for (const Case& c : cases) {
    const std::string text = R"({"kasha_scene": 1, "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "medium": "fog"},
      "materials": {"m": {}}, "media": {"fog": {"sigma_s": 0, "fluorophores": [)" + c.fluorophore + R"(]}},
      "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": 1}]})";
    const std::string file = write_file("bad_fluorophore.json", text);
    const std::string e = error_of([&] { load_scene(file); });
    EXPECT_NE(e.find(c.message), std::string::npos) << c.fluorophore << "\n  got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  // A dye given by its molar absorption: ln 10 · ε c per cm, times the scene's unit (100 cm).
  const std::string molar = write_file("molar_dye.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "medium": "fog"}, "materials": {"m": {}},
    "media": {"fog": {"sigma_s": 0, "fluorophores": [{"molar_absorption": 70000, "concentration": 1e-6,
                                                      "emission": 1}]}},
    "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": 1}]})");
  const Scene scene = load_scene(molar);
  EXPECT_NEAR(scene.media.at(0).fluorophores.at(0).absorption.at(3), std::log(10.0) * 0.07 * 100, 1e-9);
}

// The shipped dye files (scenes/dyes) carry the published values they cite: fluorescein in basic
// ethanol absorbs most at 500 nm with ε = 92 300 L·mol⁻¹·cm⁻¹ and emits most near 540 nm with
// Φ = 0.97; quinine sulfate in 0.5 M H₂SO₄ has ε = 5700 at its 344 nm band, emits most near
// 450 nm, Φ = 0.546. On a 2 nm grid the peak bins' absorption is ln 10 · ε c · 100 (metres) to
// within the table's curvature over a bin.
TEST(Medium, ShippedDyesCarryTheirPublishedPeaks) {
  const std::string dyes = source_path("scenes/dyes");
  const std::string text =
      R"({"kasha_scene": 1, "wavelengths": {"min_nm": 300, "max_nm": 700, "bin_nm": 2},
    "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "medium": "water"}, "materials": {"m": {}},
    "media": {"water": {"sigma_s": 0, "fluorophores": [
      {"dye": ")" +
      dyes + R"(/fluorescein_basic_ethanol.json", "concentration": 1e-6},
      {"dye": ")" +
      dyes + R"(/quinine_sulfate_0.5M_H2SO4.json", "concentration": 2e-6, "quantum_yield": 0.5}]}},
    "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": 1}]})";
  const Scene scene = load_scene(write_file("shipped_dyes.json", text));
  struct Want {
    double epsilon, concentration, absorb_lo, absorb_hi, emit_lo, emit_hi, yield;
  };
  const Want want[2] = {{92300, 1e-6, 496, 504, 530, 550, 0.97},
                        {5700, 2e-6, 338, 352, 440, 462, 0.5}};
  const WavelengthGrid& grid = scene.grid;
  for (int f = 0; f < 2; ++f) {
    const Fluorophore& dye = scene.media.at(0).fluorophores.at(f);
    const Want& w = want[f];
    // The absorption's maximum within the long-wave band, and the emission's maximum overall.
    int peak = -1, emit = 0;
    for (int i = 0; i < grid.bins; ++i) {
      if (grid.center(i) > w.absorb_lo - 20 && grid.center(i) < w.absorb_hi + 20 &&
          (peak < 0 || dye.absorption[i] > dye.absorption[peak]))
        peak = i;
      if (dye.e_hat[i] > dye.e_hat[emit]) emit = i;
    }
    EXPECT_GT(grid.center(peak), w.absorb_lo) << f;
    EXPECT_LT(grid.center(peak), w.absorb_hi) << f;
    EXPECT_NEAR(dye.absorption[peak] / (std::log(10.0) * w.epsilon * w.concentration * 100), 1,
                0.02)
        << f;
    EXPECT_GT(grid.center(emit), w.emit_lo) << f;
    EXPECT_LT(grid.center(emit), w.emit_hi) << f;
    EXPECT_DOUBLE_EQ(dye.quantum_yield, w.yield) << f;  // the file's, or the entry's over it
  }
  // A dye file's entry names its concentration and nothing the file gives.
  const std::string fluorescein = dyes + "/fluorescein_basic_ethanol.json";
  const std::string not_a_dye =
      write_file("not_a_dye.json", R"({"molar_absorption": 1, "emission": 1, "quantum_yield": 1})");
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"dye": ")" + fluorescein + R"("})", "missing required key \"concentration\""},
      {R"({"dye": ")" + fluorescein + R"(", "concentration": 1e-6, "emission": 1})",
       "a fluorophore with a \"dye\" file takes its \"emission\" from it"},
      {R"({"dye": ")" + not_a_dye + R"(", "concentration": 1e-6})", "not a kasha dye file"},
      {R"({"dye": ")" + dyes + R"(/absent.json", "concentration": 1e-6})", "absent.json"},
  };
  for (const auto& [entry, message] : bad) {
    const std::string e = error_of([&] {
      load_scene(write_file(
          "bad_dye.json",
          R"({"kasha_scene": 1, "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "medium": "fog"},
      "materials": {"m": {}}, "media": {"fog": {"sigma_s": 0, "fluorophores": [)" +
              entry + R"(]}},
      "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": 1}]})"));
    });
    EXPECT_NE(e.find(message), std::string::npos) << entry << "\n  got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

// Single scattering in a thin slab under a collimated beam, against its closed form. A distant
// light of irradiance E at cos θl = μl lights a slab of depth d (an interface box, wide enough to
// be a slab where it is seen: light reaches the seen points from 0.2 across at most); an orthographic camera at cos θv = μv sees it from above, with
// --max-depth 1 so that paths scatter once. Along the camera's ray, depth z = s μv:
//   L = ∫₀^{d/μv} σs p(θ) E e^{−σt z/μl} e^{−σt s} ds = σs p E (1 − e^{−σt d (1/μl + 1/μv)}) / (σt (1 + μv/μl)),
// per bin, with the Henyey–Greenstein p at the angle between the two directions.
TEST(Medium, SingleScatteringInAThinSlabFollowsItsClosedForm) {
  const double d = 0.2, g = 0.4;
  const Eigen::Vector3d to_light = Eigen::Vector3d(0.6, 1, 0.2).normalized(),
                        to_camera = Eigen::Vector3d(-0.3, 1, -0.4).normalized();
  const Eigen::Vector3d eye = 3 * to_camera;
  const double mu_l = to_light.y(), mu_v = to_camera.y(), c = to_camera.dot(to_light);
  const double phase = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g + 2 * g * c, 1.5));
  // Then with a dye: light absorbed at λj on its way in (σt_j) and re-emitted at λi on its way out
  // (σt_i), isotropically,
  //   L_i += Φ ê_i / 4π Σ_j a_j E_j (1 − e^{−(d/μv)(σt_j μv/μl + σt_i)}) / (σt_j μv/μl + σt_i).
  for (const std::string& dye : {std::string(), std::string(R"(, "fluorophores": [{"absorption": {"nm": [380, 780],
      "value": [2.5, 0.0]}, "quantum_yield": 0.8, "emission": {"gaussian_nm": 620, "fwhm_nm": 80}}])")}) {
    std::ostringstream text;
    text << R"({"kasha_scene": 1,
      "camera": {"position": [)" << eye.x() << ", " << eye.y() << ", " << eye.z() << R"(], "look_at": [0, 0, 0],
                 "type": "orthographic", "screen_window": [-0.05, 0.05, -0.05, 0.05], "width": 8, "height": 8},
      "wavelengths": {"min_nm": 380, "max_nm": 780, "bin_nm": 40},
      "media": {"mist": {"sigma_a": {"nm": [380, 780], "value": [0.2, 1.0]},
                         "sigma_s": {"nm": [380, 780], "value": [3.0, 0.5]}, "g": )" << g << dye << R"(}},
      "materials": {"m": {}},
      "shapes": [{"type": "box", "min": [-1, )" << -d << R"(, -1], "max": [1, 0, 1], "interface": true,
                  "medium": {"inside": "mist"}}],
      "lights": [{"type": "distant", "from": [)" << to_light.x() << ", " << to_light.y() << ", " << to_light.z()
         << R"(], "to": [0, 0, 0], "irradiance": 0.01}]})";
    const std::string path = write_file("single_scattering.json", text.str());
    const Scene scene = load_scene(path);
    const Medium& m = scene.media.at(0);
    const std::vector<double>& e = scene.lights.at(0).per_bin;
    const size_t n = m.sigma_s.size();
    std::vector<double> truth(n), st(n);
    for (size_t i = 0; i < n; ++i) {
      st[i] = m.sigma_a[i] + m.sigma_s[i];
      for (const Fluorophore& f : m.fluorophores) st[i] += f.absorption[i];
    }
    for (size_t i = 0; i < n; ++i) {
      truth[i] = m.sigma_s[i] * phase * e[i] * (1 - std::exp(-st[i] * d * (1 / mu_l + 1 / mu_v))) /
                 (st[i] * (1 + mu_v / mu_l));
      for (const Fluorophore& f : m.fluorophores)
        for (size_t j = 0; j < n; ++j) {
          const double k = st[j] * mu_v / mu_l + st[i];
          truth[i] += f.quantum_yield * f.e_hat[i] / (4 * M_PI) * f.absorption[j] * e[j] *
                      (1 - std::exp(-d / mu_v * k)) / k;
        }
    }
    const std::string what = dye.empty() ? "single scattering" : "single scattering with a dye";
    RenderSettings s;
    s.integrator = "backward";
    s.integrator_settings.spp = 64;
    s.integrator_settings.max_depth = 1;
    s.passes = 4;
    expect_bins_match(render_scene(path, s), truth, 0.02, what);
    // Light tracing from the distant light: each photon's first collision splatted to the camera.
    s.integrator = "forward";
    s.integrator_settings.photons = 1 << 20;
    expect_bins_match(render_scene(path, s), truth, 0.03, "forward " + what);
    // Photon mapping at one scattering vertex: next-event estimation at the visible points in the
    // medium alone, unweighed (no photon makes a path that short).
    s.integrator = "photon";
    s.integrator_settings.photons = 1 << 12;
    expect_bins_match(render_scene(path, s), truth, 0.02, "photon " + what);
    // bpt and vcm: next-event estimation at the camera's collisions weighed against light
    // tracing from the light's; ppm: the light's first collisions merged in 3-D.
    for (const std::string integrator : {"bpt", "vcm", "ppm"}) {
      s.integrator = integrator;
      s.integrator_settings.photons = 1 << 12;
      s.passes = 16;
      expect_bins_match(render_scene(path, s), truth, 0.03, integrator + " " + what);
    }
    s.passes = 4;
  }
}

}  // namespace

namespace {

// A grid medium's density (docs/media.md#grid-media): 3 × 2 × 4 samples over a box of [-0.8, 0.9]
// × [-1, 0.7] × [0.5, 1.5], turned 20° about z (its "transform"), so the camera's window sees
// parts of it, its edges, and parts with no grid at all.
constexpr int kGridX = 3, kGridY = 2, kGridZ = 4;
const double kGridValues[kGridX * kGridY * kGridZ] = {0.5, 2.0,  1.0, 0.2, 3.0, 0.7, 1.5, 0.1,
                                                      2.5, 0.9,  0.3, 1.8, 2.2, 0.4, 1.1, 0.6,
                                                      2.8, 0.05, 1.3, 0.8, 0.0, 1.9, 2.4, 1.2};
const Eigen::Vector3d kGridMin(-0.8, -1, 0.5), kGridMax(0.9, 0.7, 1.5);
constexpr double kGridTurnDeg = 20;

std::string grid_density_json() {
  std::string values;
  for (double v : kGridValues) values += (values.empty() ? "" : ", ") + std::to_string(v);
  return R"("density": {"size": [3, 2, 4], "values": [)" + values + R"(]},
            "bounds": {"min": [-0.8, -1, 0.5], "max": [0.9, 0.7, 1.5]},
            "transform": {"rotate": {"axis": [0, 0, 1], "deg": 20}})";
}

// The samples of an nx × ny × nz lattice over the grid tests' turned box around a world point and
// their trilinear weights, as pbrt-v4's SampledGrid::Lookup takes them (samples at the cells'
// centres, none past them), written out here on their own; f(sample index, weight) for each.
template <typename F>
void lattice_weights(const Eigen::Vector3d& world, const int (&n)[3], F&& f) {
  const Eigen::Vector3d p =
      Eigen::AngleAxisd(-kGridTurnDeg * M_PI / 180, Eigen::Vector3d::UnitZ()) * world;
  if ((p.array() < kGridMin.array()).any() || (p.array() > kGridMax.array()).any()) return;
  const Eigen::Vector3d u = (p - kGridMin).cwiseQuotient(kGridMax - kGridMin);
  const double q[3] = {u.x() * n[0] - 0.5, u.y() * n[1] - 0.5, u.z() * n[2] - 0.5};
  for (int corner = 0; corner < 8; ++corner) {
    double w = 1;
    int i[3];
    for (int a = 0; a < 3; ++a) {
      const int lo = static_cast<int>(std::floor(q[a]));
      const double frac = q[a] - lo;
      i[a] = lo + ((corner >> a) & 1);
      w *= (corner >> a) & 1 ? frac : 1 - frac;
    }
    if (i[0] >= 0 && i[1] >= 0 && i[2] >= 0 && i[0] < n[0] && i[1] < n[1] && i[2] < n[2])
      f((i[2] * n[1] + i[1]) * n[0] + i[0], w);
  }
}

// The density at a world point.
double grid_density(const Eigen::Vector3d& world) {
  double sum = 0;
  lattice_weights(world, {kGridX, kGridY, kGridZ},
                  [&](int v, double w) { sum += w * kGridValues[v]; });
  return sum;
}

}  // namespace

// The slab of dye replaced by a grid of it: the camera's window, [-1, 1]², sees the lamp through
// exp(−σa,i ∫ density dz) and 2 units of haze. The truth is the window's mean of that, the
// integral by the midpoint rule in 400 steps (its error ~10⁻⁶) over 160 × 160 points; backward and
// light tracing against it per bin, within 0.5 %. Measured: the largest bin's difference 0.01 %
// (backward), 0.06 % (forward); the density taken at the nearest sample instead of trilinear was
// 11 % off, the grid not turned 4.7 %.
TEST(Medium, AnEmitterSeenThroughAGridOfDyeFollowsItsIntegral) {
  std::string scene = slab_scene();
  scene.replace(scene.find(R"("dye": {)"), 8,
                R"("dye": {"type": "grid", )" + grid_density_json() + ", ");
  const std::string path = write_file("medium_grid_slab.json", scene);
  const Scene loaded = load_scene(path);
  ASSERT_TRUE(loaded.media.at(0).grid.has_value());
  std::vector<double> truth(loaded.media.at(0).sigma_a.size(), 0.0);
  constexpr int kSide = 160, kSteps = 400;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      double optical = 0;
      for (int k = 0; k < kSteps; ++k)
        optical += grid_density(
            {-1 + (x + 0.5) * 2 / kSide, -1 + (y + 0.5) * 2 / kSide, 0.5 + (k + 0.5) / kSteps});
      optical /= kSteps;
      for (size_t i = 0; i < truth.size(); ++i)
        truth[i] += std::exp(-loaded.media.at(0).sigma_a[i] * optical - 2 * 0.1) / (kSide * kSide);
    }
  for (const std::string integrator : {"backward", "forward"}) {
    expect_emitter_seen_through(path, integrator, truth, 0.005, integrator + " through the grid");
  }
}

// The scattering furnace with the ball's medium on a grid (the same density, stretched over the
// ball's box): light neither lost nor made, so L everywhere in every integrator. Merges divide by
// the density where the camera path collides (photon mapping's and vcm's stored collisions are
// denser by it); without that division photon mapping was up to +24 % off and ppm over +28 % (vcm,
// whose merges weigh little beside its connections here, still passed).
TEST(Medium, AGriddedScatteringFurnaceShowsTheEmittersRadiance) {
  std::string density = grid_density_json();
  density.replace(density.find(R"("bounds")"), std::string::npos,
                  R"("bounds": {"min": [-0.7, -0.7, -0.7], "max": [0.7, 0.7, 0.7]}})");
  const std::string scene = sphere_furnace(
      R"({"type": "grid", "sigma_a": 0, "sigma_s": {"nm": [380, 780], "value": [4.0, 0.5]}, "g": 0.5, )" +
      density);
  for (const std::string integrator : {"backward", "forward", "photon", "vcm", "bpt", "ppm"}) {
    RenderResult r = render_furnace("grid_furnace.json", scene, integrator);
    ASSERT_TRUE(r.scene.scattering());
    expect_bins_match(r, r.scene.emitters.at(0).per_bin, integrator == "backward" ? 0.02 : 0.05,
                      integrator + " grid furnace");
  }
}

namespace {

// The error of loading a scene whose medium "fog", the camera's, is {"type": TYPE, ENTRY}.
std::string bad_medium_error(const std::string& type, const std::string& entry) {
  const std::string text =
      R"({"kasha_scene": 1, "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "medium": "fog"},
      "materials": {"m": {}}, "media": {"fog": {"type": ")" +
      type + "\", " + entry + R"(}},
      "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": 1}]})";
  return error_of([&] { load_scene(write_file("bad_medium.json", text)); });
}

// The error of importing a pbrt-v4 file that makes the medium "smoke" of TYPE with PARAMS.
std::string bad_pbrt_medium_error(const std::string& type, const std::string& params) {
  const std::string text = "Camera \"perspective\"\nWorldBegin\nMakeNamedMedium \"smoke\" \"string type\" \"" +
                           type + "\" " + params + "\n";
  return error_of([&] { import_pbrt_scene(write_file("bad_medium.pbrt", text), {}); });
}

// One line that says `message`.
void expect_one_line(const std::string& e, const std::string& message, const std::string& input) {
  EXPECT_NE(e.find(message), std::string::npos) << input << "\n  got: " << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// The JSON entry pbrt-v4's `MakeNamedMedium "smoke" "string type" TYPE_AND_PARAMS` imports as,
// made under Translate 1 2 3 and put in an interface sphere.
nlohmann::json imported_medium(const std::string& type_and_params) {
  const nlohmann::json s = import_pbrt_scene(write_file("grid.pbrt", R"(
LookAt 0 1 3  0 0 0  0 1 0
Camera "perspective"
WorldBegin
AttributeBegin
  Translate 1 2 3
  MakeNamedMedium "smoke" "string type" )" + type_and_params + R"(
AttributeEnd
AttributeBegin
  MediumInterface "smoke" ""
  Material "interface"
  Shape "sphere"
AttributeEnd
)"),
                                             {});
  return s.at("media").at("smoke");
}

}  // namespace

TEST(Medium, BadGridsAreOneLine) {
  struct Case {
    std::string grid, message;
  };
  const std::vector<Case> cases = {
      {R"("density": {"size": [2, 2, 2], "values": [1, 1, 1]})", "needs 8 values, not 3"},
      {R"("density": {"size": [2, 1, 1], "values": [1, -1]})",
       "a density must be finite and not negative"},
      {R"("density": {"size": [0, 1, 1], "values": []})", "each size must be a whole number"},
      {R"("density": {"size": [1, 1], "values": [1]})", "expected [nx, ny, nz]"},
      {R"("density": {"size": [1, 1, 1], "values": [1]}, "bounds": {"min": [0, 0, 0], "max": [1, 0, 1]})",
       "each of \"min\" must be below \"max\""},
      {R"("sigma_s": 1)", "a grid medium needs its \"density\""},
      {R"("density": {"size": [1, 1, 2], "values": [1, 1]}, "temperature": {"values": [900]})",
       "samples need 2 values, not 1"},
      {R"("density": {"size": [1, 1, 1], "values": [1]}, "temperature": {"values": [900]},
          "emission": 1)",
       "a spectrum (\"emission\") or a blackbody (\"temperature\"), not both"},
      {R"("density": {"size": [1, 1, 1], "values": [1]}, "temperature_scale": 2)",
       "only with a \"temperature\""},
      {R"("density": {"size": [1, 1, 1], "values": [1]}, "emission_scale": 2)", "which it has not"},
      {R"("density": {"size": [1, 1, 1], "values": [1]}, "emission": 1,
          "emission_scale": {"values": [-1]})",
       "must be finite and not negative"},
  };
  for (const Case& c : cases) expect_one_line(bad_medium_error("grid", c.grid), c.message, c.grid);
  const std::vector<Case> pbrt = {
      {R"("integer nx" 2 "float density" [1 1 1])", "3 density values for nx*ny*nz = 2"},
      {R"("float density" [-1])", "a density must be finite and not negative"},
      {R"("float density" [1] "point3 p0" [0 0 0] "point3 p1" [1 1 0])",
       "\"p0\" and \"p1\" must differ"},
      {R"("float density" [1] "float temperature" [1 2])", "different number of samples (1 vs 2)"},
      {R"("float density" [1] "float temperature" [900] "rgb Le" [1 1 1])",
       "both \"Le\" and \"temperature\""},
      {R"("integer nx" 2 "float density" [1 1] "float Lescale" [1])",
       "expected 2 values for \"Lescale\""},
      {R"("integer nx" 1)", "no \"density\" value provided"},
  };
  for (const Case& c : pbrt)
    expect_one_line(bad_pbrt_medium_error("uniformgrid", c.grid), c.message, c.grid);
}

// pbrt-v4's uniformgrid: its samples, box and transform as kasha's grid medium.
TEST(Medium, PbrtUniformGridImportsAsKashasGrid) {
  const nlohmann::json m =
      imported_medium(R"("uniformgrid" "integer nx" 2 "integer ny" 1 "integer nz" 1
    "float density" [0.5 2] "point3 p0" [-1 -1 -1] "point3 p1" [1 1 1] "rgb sigma_a" [1 1 1] "rgb sigma_s" [2 2 2] "float scale" 3)");
  EXPECT_EQ(m.at("type"), "grid");
  EXPECT_EQ(m.at("density").at("size"), nlohmann::json::parse("[2, 1, 1]"));
  EXPECT_EQ(m.at("density").at("values"), nlohmann::json::parse("[0.5, 2.0]"));
  EXPECT_EQ(m.at("bounds").at("min"), nlohmann::json::parse("[-1.0, -1.0, -1.0]"));
  EXPECT_EQ(m.at("transform").at("matrix").at(3), 1.0);  // the translation's x
  EXPECT_EQ(m.at("scale"), 3.0);
}

namespace {

// A colour grid (docs/media.md#colour-grids): 4 × 3 × 4 samples over the grid tests' turned box,
// each sample's colour an RGB: with `distinct` each its own (48 colours: more than the bins, so a
// component per bin), else one of three colours times a factor (three components).
constexpr int kColourN[3] = {4, 3, 4};
constexpr int kColourSamples = 4 * 3 * 4;

std::array<double, 3> sample_colour(int v, bool distinct) {
  const double factor = 0.3 + 0.25 * ((v * 7) % 11);
  if (distinct)
    return {factor * (0.2 + 0.8 * ((v * 5) % 13) / 12.0),
            factor * (0.2 + 0.8 * ((v * 3) % 17) / 16.0),
            factor * (0.2 + 0.8 * ((v * 11) % 19) / 18.0)};
  const double base[3][3] = {{1, 0.3, 0.1}, {0.2, 0.6, 1}, {0.5, 1, 0.4}};
  return {factor * base[v % 3][0], factor * base[v % 3][1], factor * base[v % 3][2]};
}

// `"size", "sigma_a", "sigma_s", "bounds", "transform"` of an rgbgrid entry: the colours as σa
// (σs 0) or, with `scattering`, as σs (σa 0), over `bounds`.
std::string colour_grid_json(bool distinct, bool scattering, const std::string& bounds) {
  std::string colours, zeros;
  for (int v = 0; v < kColourSamples; ++v)
    for (double c : sample_colour(v, distinct)) {
      colours += (colours.empty() ? "" : ", ") + std::to_string(c);
      zeros += zeros.empty() ? "0" : ", 0";
    }
  const std::string a = scattering ? zeros : colours, sc = scattering ? colours : zeros;
  return R"("type": "rgbgrid", "size": [4, 3, 4], "sigma_a": {"rgb_values": [)" + a +
         R"(]}, "sigma_s": {"rgb_values": [)" + sc + R"(]}, "bounds": )" + bounds +
         R"(, "transform": {"rotate": {"axis": [0, 0, 1], "deg": 20}})";
}

// Sample v's spectrum on the grid's bins, each the mean of pbrt-v4's RGBUnboundedSpectrum (the
// sigmoid of rgb / 2m times 2m, m its largest part) at 20 points across the bin.
std::vector<double> sample_spectrum(int v, bool distinct, const WavelengthGrid& grid) {
  double scale = 0;
  const SigmoidCoefficients c = rgb_unbounded_sigmoid(sample_colour(v, distinct), &scale);
  std::vector<double> out(grid.bins, 0.0);
  for (int i = 0; i < grid.bins; ++i)
    for (int k = 0; k < 20; ++k)
      out[i] += scale * sigmoid_spectrum(c, grid.lo(i) + (k + 0.5) * grid.bin_nm / 20) / 20;
  return out;
}

}  // namespace

// The components rebuild every sample's spectrum: Σ_k ρ_k(v) σt_k = σa_v + σs_v and Σ_k ρ_k(v) σs_k
// = σs_v per bin, to float precision, with three components per coefficient for three colours and
// one per bin for 48; an absent colour list is one box-wide component of 1 (pbrt-v4's), last.
TEST(Medium, AColourGridsComponentsRebuildEverySample) {
  WavelengthGrid grid;
  for (const bool distinct : {false, true}) {
    DensityGrid g;
    g.nx = 4, g.ny = 3, g.nz = 4;
    for (int v = 0; v < kColourSamples; ++v)
      for (double c : sample_colour(v, distinct)) {
        g.sigma_a_rgb.push_back(static_cast<float>(c));
        g.sigma_s_rgb.push_back(static_cast<float>(c / 2));
      }
    const std::vector<GridComponent> k = colour_grid_components(g, 1.5, grid);
    EXPECT_EQ(k.size(), distinct ? 2u * grid.bins : 6u);
    for (int v = 0; v < kColourSamples; ++v) {
      const std::vector<double> a = sample_spectrum(v, distinct, grid);
      for (int i = 0; i < grid.bins; ++i) {
        double t = 0, sc = 0;
        for (const GridComponent& c : k)
          t += c.values[v] * c.sigma_t[i], sc += c.values[v] * c.sigma_s[i];
        // σs's colours are half σa's: the same spectra, half the size.
        EXPECT_NEAR(t, 1.5 * 1.5 * a[i], 2e-5 * (1 + a[i]))
            << v << " bin " << i << " distinct " << distinct;
        EXPECT_NEAR(sc, 1.5 * 0.5 * a[i], 2e-5 * (1 + a[i])) << v << " bin " << i;
      }
    }
    g.sigma_s_rgb.clear();
    const std::vector<GridComponent> u = colour_grid_components(g, 2, grid);
    ASSERT_FALSE(u.empty());
    EXPECT_TRUE(u.back().values.empty());
    for (int i = 0; i < grid.bins; ++i) {
      EXPECT_EQ(u.back().sigma_t[i], 2.0);
      EXPECT_EQ(u.back().sigma_s[i], 2.0);
    }
  }
}

// The slab of dye replaced by a colour grid of absorption: the window sees the lamp through
// exp(−∫ σa,i(x) dz) per bin, σa,i(x) = Σ_v w_v(x) σa_v,i interpolating the samples' own spectra
// (sample_spectrum), and 2 units of haze; the integral by the midpoint rule in 400 steps over
// 100 × 100 points. Backward within 0.5 % per bin, for three colours (three components) and for
// 48 (a component per bin).
TEST(Medium, AnEmitterSeenThroughAColourGridFollowsItsIntegral) {
  for (const bool distinct : {false, true}) {
    std::string scene = slab_scene();
    const size_t at = scene.find(R"("dye": {)"),
                 end = scene.find('}', scene.find(R"("sigma_s")", at));
    scene.replace(at, end + 1 - at,
                  R"("dye": {)" +
                      colour_grid_json(distinct, false,
                                       R"({"min": [-0.8, -1, 0.5], "max": [0.9, 0.7, 1.5]})") +
                      ", \"scale\": 0.8}");
    const std::string path = write_file("medium_colour_slab.json", scene);
    const Scene loaded = load_scene(path);
    ASSERT_EQ(loaded.media.at(0).components.size(), distinct ? size_t(loaded.grid.bins) : 3u);
    std::vector<std::vector<double>> spectra;
    for (int v = 0; v < kColourSamples; ++v)
      spectra.push_back(sample_spectrum(v, distinct, loaded.grid));
    std::vector<double> truth(loaded.grid.bins, 0.0);
    constexpr int kSide = 100, kSteps = 400;
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        double weight[kColourSamples] = {};
        for (int k = 0; k < kSteps; ++k)
          lattice_weights(
              {-1 + (x + 0.5) * 2 / kSide, -1 + (y + 0.5) * 2 / kSide, 0.5 + (k + 0.5) / kSteps},
              kColourN, [&](int v, double w) { weight[v] += w / kSteps; });
        for (int i = 0; i < loaded.grid.bins; ++i) {
          double optical = 0;
          for (int v = 0; v < kColourSamples; ++v) optical += weight[v] * 0.8 * spectra[v][i];
          truth[i] += std::exp(-optical - 2 * 0.1) / (kSide * kSide);
        }
      }
    expect_emitter_seen_through(path, "backward", truth, 0.005,
                                distinct ? "through 48 colours" : "through three colours");
  }
}

// An emitting colour grid (pbrt-v4's rgbgrid with "Le") seen face on against black, its σa and Le
// colours varying along z over 12 samples (σa in three colours up to a factor: three components;
// Le in 12, more than the 10 bins: a component per bin): in each bin
//   L = ∫ σa(z) Le(z) exp(−∫_z^top σa) dz,
// σa and Le each interpolated between the samples' own spectra (pbrt-v4's RGBUnboundedSpectrum
// and RGBIlluminantSpectrum), by the midpoint rule in 4000 steps. Backward and vcm (camera paths
// take σa·Le at their collisions, from the point's own σa) and forward (photons start at points
// of the grid's box) within 4 standard errors and 2 % per bin.
TEST(Medium, AnEmittingColourGridFollowsItsIntegral) {
  constexpr int kZ = 12;
  std::vector<std::array<double, 3>> sigma, le;
  const std::array<std::array<double, 3>, 3> base = {
      {{1, 0.5, 0.2}, {0.3, 0.8, 1.2}, {0.9, 0.9, 0.1}}};
  for (int k = 0; k < kZ; ++k) {
    const double f = 0.6 + 0.15 * (k % 5);
    sigma.push_back({f * base[k % 3][0], f * base[k % 3][1], f * base[k % 3][2]});
    le.push_back({0.2 + 0.1 * k, 1.0 - 0.06 * k, 0.3 + 0.02 * k * k});
  }
  const auto lattice = [&](const std::vector<std::array<double, 3>>& c) {  // 2 × 2 × kZ
    std::string out;
    for (int v = 0; v < 4 * kZ; ++v)
      for (double x : c[v / 4]) out += (out.empty() ? "" : ", ") + std::to_string(x);
    return "{\"rgb_values\": [" + out + "]}";
  };
  const std::string medium = R"({"type": "rgbgrid", "size": [2, 2, 12], "sigma_a": )" +
                             lattice(sigma) + R"(, "sigma_s": )" +
                             lattice(std::vector<std::array<double, 3>>(kZ, {0, 0, 0})) +
                             R"(, "emission": )" + lattice(le) + R"(, "emission_scale": 0.7,
      "scale": 1.5, "bounds": {"min": [-3, -3, 0.5], "max": [3, 3, 1.5]}})";
  const std::string path =
      emitting_box_scene("emitting_colour_grid.json", medium,
                         R"("wavelengths": {"min_nm": 380, "max_nm": 780, "bin_nm": 40},)");
  const Scene scene = load_scene(path);
  const WavelengthGrid& grid = scene.grid;
  ASSERT_EQ(scene.media.at(0).components.size(), 3u);
  ASSERT_EQ(scene.media.at(0).emission_components.size(), size_t(grid.bins));
  std::vector<std::vector<double>> sa, ra;  // per sample along z, per bin
  for (int k = 0; k < kZ; ++k) {
    double scale = 0;
    const SigmoidCoefficients c = rgb_unbounded_sigmoid(sigma[k], &scale);
    sa.emplace_back(grid.bins, 0.0);
    for (int i = 0; i < grid.bins; ++i)
      for (int n = 0; n < 20; ++n)
        sa[k][i] +=
            1.5 * scale * sigmoid_spectrum(c, grid.lo(i) + (n + 0.5) * grid.bin_nm / 20) / 20;
    ra.push_back(grid.resample(RgbIlluminantSpectrum(le[k])));
    for (double& v : ra[k]) v *= 0.7;
  }
  const auto along = [&](const std::vector<std::vector<double>>& f, int i, double z) {
    const double q = (z - 0.5) * kZ - 0.5, k = std::floor(q);
    const auto at = [&](double j) { return j < 0 || j > kZ - 1 ? 0.0 : f[size_t(j)][i]; };
    return at(k) + (at(k + 1) - at(k)) * (q - k);
  };
  std::vector<double> expected(grid.bins, 0.0);
  const int steps = 4000;
  for (int i = 0; i < grid.bins; ++i) {
    double depth = 0;  // ∫ σa from the top down to z
    for (int k = 0; k < steps; ++k) {
      const double z = 1.5 - (k + 0.5) / steps, dz = 1.0 / steps, a = along(sa, i, z);
      expected[i] += a * along(ra, i, z) * std::exp(-(depth + 0.5 * a * dz)) * dz;
      depth += a * dz;
    }
  }
  for (const std::string integrator : {"backward", "vcm", "forward"}) {
    RenderSettings settings;
    settings.integrator = integrator;
    settings.integrator_settings.spp = 64;
    settings.passes = 4;
    const RenderResult r = render_scene(path, settings);
    expect_bins_match(r, expected, 0.02, integrator + " emitting colour grid", true);
  }
}

// The scattering furnace with a colour grid of σs (σa 0) over the ball's box: L everywhere, in
// every integrator for three colours, and in backward and vcm for 48 (a component per bin: the
// furnace has 10). The collisions' coefficients are the point's own, the merges take no density.
TEST(Medium, AColourGridScatteringFurnaceShowsTheEmittersRadiance) {
  const std::string box = R"({"min": [-0.7, -0.7, -0.7], "max": [0.7, 0.7, 0.7]})";
  for (const bool distinct : {false, true}) {
    const std::string scene = sphere_furnace("{" + colour_grid_json(distinct, true, box) +
                                             R"(, "g": 0.5, "scale": 0.7})");
    const std::vector<std::string> integrators =
        distinct ? std::vector<std::string>{"backward", "vcm"}
                 : std::vector<std::string>{"backward", "forward", "photon", "vcm", "bpt", "ppm"};
    for (const std::string& integrator : integrators) {
      RenderResult r = render_furnace("colour_furnace.json", scene, integrator);
      ASSERT_TRUE(r.scene.scattering());
      ASSERT_EQ(r.scene.media.at(0).components.size(), distinct ? 10u : 3u);
      expect_bins_match(r, r.scene.emitters.at(0).per_bin, integrator == "backward" ? 0.02 : 0.05,
                        integrator + (distinct ? " 48-colour furnace" : " three-colour furnace"));
    }
  }
}

// pbrt-v4's rgbgrid: its colours, box, transform, scale, g and emission as kasha's; its refusals
// as pbrt-v4's, one line each.
TEST(Medium, PbrtRgbGridImportsAsKashas) {
  const nlohmann::json m = imported_medium(R"("rgbgrid" "integer nx" 2 "integer ny" 1 "integer nz" 1
    "rgb sigma_a" [0.5 1 2  0 0 0] "point3 p0" [-1 -1 -1] "point3 p1" [1 1 1] "float scale" 3 "float g" 0.4)");
  EXPECT_EQ(m.at("type"), "rgbgrid");
  EXPECT_EQ(m.at("size"), nlohmann::json::parse("[2, 1, 1]"));
  EXPECT_EQ(m.at("sigma_a").at("rgb_values"),
            nlohmann::json::parse("[0.5, 1.0, 2.0, 0.0, 0.0, 0.0]"));
  EXPECT_FALSE(m.contains("sigma_s"));  // 1 in the whole box
  EXPECT_EQ(m.at("transform").at("matrix").at(3), 1.0);
  EXPECT_EQ(m.at("scale"), 3.0);
  EXPECT_EQ(m.at("g"), 0.4);
  EXPECT_FALSE(m.contains("emission"));
  // An emitting one: its "Le" colours (an illuminant's: XYZ kept from another ColorSpace) and
  // "Lescale"; none at Lescale 0, as pbrt-v4's IsEmissive.
  const nlohmann::json e = imported_medium(R"("rgbgrid" "integer nx" 2
    "rgb sigma_a" [0.5 1 2  1 1 1] "rgb Le" [1 2 3  0 0.5 0] "float Lescale" 4)");
  EXPECT_EQ(e.at("emission").at("rgb_values"),
            nlohmann::json::parse("[1.0, 2.0, 3.0, 0.0, 0.5, 0.0]"));
  EXPECT_EQ(e.at("emission_scale"), 4.0);
  EXPECT_FALSE(
      imported_medium(R"("rgbgrid" "rgb sigma_a" [1 1 1] "rgb Le" [1 1 1] "float Lescale" 0)")
          .contains("emission"));
  struct Case {
    std::string grid, message;
  };
  const std::vector<Case> pbrt = {
      {R"("integer nx" 2)", "RGB grid requires \"sigma_a\" and/or \"sigma_s\""},
      {R"("rgb sigma_a" [1 1 1] "rgb sigma_s" [1 1 1 1 1 1])",
       "Different number of samples (1 vs 2)"},
      {R"("integer nx" 2 "rgb sigma_a" [1 1 1])", "has 1 density values; expected nx*ny*nz = 2"},
      {R"("rgb sigma_a" [1 -1 1])", "has a negative component"},
      {R"("rgb sigma_s" [1 1 1] "rgb Le" [1 1 1])", "requires \"sigma_a\" if \"Le\""},
      {R"("rgb sigma_a" [1 1 1] "rgb Le" [1 1 1 1 1 1])",
       "Expected 1 values for \"Le\" parameter but were given 2."},
      {R"("rgb sigma_a" [1 1 1] "rgb Le" [1 1 -1])", "\"rgb Le\" has a negative component"},
  };
  for (const Case& c : pbrt)
    expect_one_line(bad_pbrt_medium_error("rgbgrid", c.grid), c.message, c.grid);
  const std::vector<Case> json = {
      {R"("size": [1, 1, 1], "sigma_a": {"rgb_values": [1, 1]})", "needs 3 values, not 2"},
      {R"("size": [1, 1, 1], "sigma_s": {"rgb_values": [1, -1, 1]})",
       "a colour must be finite and not negative"},
      {R"("size": [1, 1, 1])", "an rgbgrid needs \"sigma_a\" or \"sigma_s\" colours"},
      {R"("size": [1, 1, 1], "sigma_a": 1)", "expected {\"rgb_values\""},
      {R"("size": [1, 1, 1], "sigma_a": {"rgb_values": [1, 1, 1]}, "emission": 1)",
       "expected {\"rgb_values\""},
      {R"("size": [1, 1, 1], "sigma_s": {"rgb_values": [1, 1, 1]}, "emission": {"rgb_values": [1, 1, 1]})",
       "its emission needs \"sigma_a\" colours"},
      {R"("size": [1, 1, 2], "sigma_a": {"rgb_values": [1, 1, 1, 1, 1, 1]}, "emission": {"rgb_values": [1, 1, 1]})",
       "needs 6 values, not 3"},
      {R"("size": [1, 1, 1], "sigma_a": {"rgb_values": [1, 1, 1]}, "emission": {"rgb_values": [1, 1, 1]},
          "emission_scale": {"values": [1]})",
       "an rgbgrid's emission scale is a number"},
      {R"("size": [1, 1, 1], "sigma_a": {"rgb_values": [1, 1, 1]}, "temperature": {"values": [1]})",
       "an rgbgrid medium takes no \"temperature\""},
  };
  for (const Case& c : json) expect_one_line(bad_medium_error("rgbgrid", c.grid), c.message, c.grid);
}
