// Smooth dielectrics and conductors (docs/materials.md) against ground truth computed here, in
// double, independently of the kernels:
// - a non-absorbing glass object (eta 1.5) and an air bubble (eta 0.75) inside a uniformly
//   emitting black enclosure: every pixel sees exactly the enclosure's radiance (backward, photon
//   mapping); light tracing shows them black, and `render` says so once;
// - a glass slab in front of a lamp transmits (1 − F)/(1 + F) of its radiance (Fresnel's F at
//   the angle of incidence, the internal reflections summed), at normal and at 60° incidence;
// - a gold floor in the enclosure shows the enclosure times gold's Fresnel reflectance at each
//   pixel's angle, from n + ik (the same in every bin).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

double fresnel(double cos_i, std::complex<double> m) {
  return fresnel_reference(cos_i, m);
}

RenderResult render_with(const std::string& scene, const std::string& integrator, int spp) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = 1;
  s.integrator_settings.spp = spp;
  s.integrator_settings.photons = 1 << 12;
  return render_scene(scene, s);
}

// The enclosure's radiance per bin: the first emitter's.
const std::vector<double>& enclosure(const Scene& scene) {
  return scene.emitters.front().per_bin;
}

// Every lit bin of every listed pixel within `tolerance` of truth(pixel, bin).
template <class Truth>
void expect_pixels(const RenderResult& r, const std::vector<size_t>& pixels, double tolerance,
                   Truth truth, const std::string& label) {
  const std::vector<double>& le = enclosure(r.scene);
  const double peak = *std::max_element(le.begin(), le.end());
  const size_t N = r.scene.grid.bins;
  int bad = 0;
  for (size_t p : pixels)
    for (size_t i = 0; i < N; ++i) {
      if (le[i] < 1e-3 * peak) continue;
      double want = truth(p, i), got = r.image.spectral[p * N + i];
      if (std::abs(got - want) > tolerance * want && ++bad <= 5)
        ADD_FAILURE() << label << ": pixel " << p << " bin " << i << ": " << got << ", want "
                      << want;
    }
  EXPECT_EQ(bad, 0) << label;
}

std::vector<size_t> all_pixels(const Image& img) {
  std::vector<size_t> p(img.pixels());
  for (size_t i = 0; i < p.size(); ++i) p[i] = i;
  return p;
}

struct FurnaceCase {
  std::string integrator, scene;
};
void PrintTo(const FurnaceCase& c, std::ostream* os) {
  *os << c.integrator << " in " << c.scene;
}

class DielectricFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// Each camera path through the glass keeps weight 1 (reflection with probability F, refraction
// with 1 − F; radiance's 1/eta² on the way in undone on the way out), so every sample is the
// enclosure's radiance, to float rounding.
TEST_P(DielectricFurnace, EveryPixelSeesTheEnclosure) {
  const FurnaceCase& c = GetParam();
  RenderResult r = render_with(source_path("scenes/" + c.scene), c.integrator, 4);
  std::map<std::string, std::vector<size_t>> regions = primary_hit_regions(r.scene, r.scene.camera);
  const std::string object = c.scene == "furnace_glass.json" ? "glass" : "bubble";
  ASSERT_GE(regions[object].size(), 40u) << "the camera sees the object";
  const std::vector<double>& le = enclosure(r.scene);
  expect_pixels(
      r, all_pixels(r.image), 2e-3, [&](size_t, size_t i) { return le[i]; },
      c.integrator + " " + c.scene);
}

INSTANTIATE_TEST_SUITE_P(Integrators, DielectricFurnace,
                         ::testing::Values(FurnaceCase{"backward", "furnace_glass.json"},
                                           FurnaceCase{"backward", "furnace_bubble.json"},
                                           FurnaceCase{"photon", "furnace_glass.json"},
                                           FurnaceCase{"photon", "furnace_bubble.json"}),
                         [](const auto& info) {
                           return info.param.integrator + "_" +
                                  info.param.scene.substr(8, info.param.scene.size() - 13);
                         });

// Light tracing cannot reach a pinhole through a delta lobe: the glass shows black, the enclosure
// seen directly does not, and the command line warns once.
TEST(SpecularMaterial, LightTracingShowsGlassBlackAndSaysSo) {
  const std::string scene = source_path("scenes/furnace_glass.json");
  RenderSettings s;
  s.integrator = "forward";
  s.passes = 1;
  s.integrator_settings.photons = 1 << 16;
  RenderResult r = render_scene(scene, s);
  std::map<std::string, std::vector<size_t>> regions = primary_hit_regions(r.scene, r.scene.camera);
  // Pixels whose neighbours all see glass too: no splat from the enclosure falls in them.
  const int w = r.image.width, h = r.image.height;
  std::vector<char> glass(r.image.pixels(), 0);
  for (size_t p : regions["glass"]) glass[p] = 1;
  int inner = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool all = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) all = all && glass[(y + dy) * w + x + dx];
      if (!all) continue;
      ++inner;
      EXPECT_EQ(r.image.xyz[3 * (y * w + x) + 1], 0.0f) << "pixel " << x << ", " << y;
    }
  EXPECT_GE(inner, 20);
  BinStats lamp = pixel_statistics(r.image, false, regions["lamp"]);
  EXPECT_GT(lamp.mean[1], 0.0);

  std::string out = (scratch_dir() / "forward_glass.exr").string();
  CommandResult run =
      run_kasha("render " + scene + " --integrator forward --passes 1 --photons 4096 -o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  size_t first = run.err.find("ideal mirrors, glass and metal");
  ASSERT_NE(first, std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("ideal mirrors, glass and metal", first + 1), std::string::npos)
      << run.err;
  CommandResult backward = run_kasha("render " + scene + " --passes 1 --spp 1 -o " + out);
  ASSERT_EQ(backward.exit_code, 0) << backward.err;
  EXPECT_EQ(backward.err.find("ideal mirrors"), std::string::npos) << backward.err;
}

// A lamp seen through a slab of glass: (1 − F)/(1 + F) of its radiance (the Fresnel reflections
// at both faces summed over internal bounces; F the same at both faces), for a slab facing the
// camera and one turned by 60°. The camera's field of view is 1°, so F is F(θ) within 1e-4; the
// lamp is small enough that light reflected off the turned slab misses it.
TEST(SpecularMaterial, AGlassSlabTransmitsTheFresnelFraction) {
  for (double deg : {0.0, 60.0}) {
    const std::string scene = write_file("slab_" + std::to_string(int(deg)) + ".json", R"({
  "kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 1, "width": 8, "height": 8},
  "materials": {"black": {}, "glass": {"dielectric": {"eta": 1.5}}},
  "shapes": [
    {"type": "box", "min": [-0.5, -0.5, -0.02], "max": [0.5, 0.5, 0.02], "material": "glass",
     "transform": {"rotate": {"axis": [0, 1, 0], "deg": )" + std::to_string(deg) + R"(}}},
    {"type": "quad", "corner": [-0.3, -0.3, -1], "u": [0.6, 0, 0], "v": [0, 0.6, 0], "material": "black",
     "emission": {"nm": [380, 780], "value": [1, 2]}}
  ]
})");
    const double F = fresnel(std::cos(deg * M_PI / 180), 1.5), T = (1 - F) / (1 + F);
    for (const char* integrator : {"backward", "photon"}) {
      RenderResult r = render_with(scene, integrator, 64);
      const std::vector<double>& le = enclosure(r.scene);
      // Each sample is exact but for the choice of reflection or refraction: within 4 standard
      // errors of a Bernoulli sum at 64 samples per pixel, over the 64 pixels' mean.
      BinStats s = pixel_statistics(r.image, true);
      for (size_t i = 0; i < le.size(); ++i) {
        double want = le[i] * T;
        EXPECT_NEAR(s.mean[i], want, 4 * s.standard_error[i] + 1e-5 * want)
            << integrator << " at " << deg << "° bin " << i;
        EXPECT_NEAR(s.mean[i], want, 0.01 * want);
      }
      // A slab that let everything through would lie far outside.
      EXPECT_GT(std::abs(s.mean[10] / le[10] - 1), 10 * s.standard_error[10] / le[10]);
    }
  }
}

// Gold reflecting the enclosure: per bin, the image mean is the enclosure's radiance times gold's
// Fresnel reflectance averaged over the pixels that see the floor (8 × 8 rays a pixel here), plus
// the pixels that see the enclosure directly.
TEST(SpecularMaterial, AGoldFloorReflectsTheFresnelReflectanceOfItsIndex) {
  const std::string path = source_path("scenes/furnace_conductor.json");
  for (const char* integrator : {"backward", "photon"}) {
    RenderResult r = render_with(path, integrator, 64);
    const Scene& scene = r.scene;
    const Material& gold = scene.materials[scene.material_index("gold")];
    ASSERT_EQ(gold.kind, MaterialKind::conductor);
    const KCamera cam = scene.camera.to_kernel();
    const size_t N = scene.grid.bins;
    std::vector<double> want(N, 0.0);
    const int sub = 8;
    for (int py = 0; py < cam.height; ++py)
      for (int px = 0; px < cam.width; ++px)
        for (int sy = 0; sy < sub; ++sy)
          for (int sx = 0; sx < sub; ++sx) {
            double u = 2 * (px + (sx + 0.5) / sub) / cam.width - 1,
                   v = 1 - 2 * (py + (sy + 0.5) / sub) / cam.height;
            double d[3], len = 0;
            for (int k = 0; k < 3; ++k) {
              d[k] = cam.forward[k] + u * cam.right[k] + v * cam.up[k];
              len += d[k] * d[k];
            }
            const double cos_i = -d[1] / std::sqrt(len);
            const double t = cam.position[1] / std::max(-d[1], 1e-12);
            const bool floor = cos_i > 0 && std::abs(cam.position[0] + t * d[0]) < 10 &&
                               std::abs(cam.position[2] + t * d[2]) < 10;
            for (size_t i = 0; i < N; ++i)
              want[i] += floor ? fresnel(cos_i, {gold.eta_c[i], gold.k_c[i]}) : 1.0;
          }
    const std::vector<double>& le = enclosure(scene);
    BinStats s = pixel_statistics(r.image, true);
    const double peak = *std::max_element(le.begin(), le.end());
    for (size_t i = 0; i < N; ++i) {
      if (le[i] < 1e-3 * peak) continue;
      double expected = le[i] * want[i] / (sub * sub * cam.width * cam.height);
      EXPECT_NEAR(s.mean[i], expected, 2e-3 * expected) << integrator << " bin " << i;
    }
  }
}

TEST(SpecularMaterial, BadDielectricsAndConductorsNameTheJsonPath) {
  auto scene_with = [](const std::string& name, const std::string& material) {
    return write_file(name, R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
  "materials": {"m": )" + material +
                                R"(},
  "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m",
              "emission": 1}]})");
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"dielectric": {"eta": 0}})", "/materials/m/dielectric/eta: eta must lie in [0.01, 100]"},
      {R"({"dielectric": {"eta": -1.5}})", "/materials/m/dielectric/eta: eta must lie in"},
      {R"({"dielectric": {"eta": 1.5, "roughnes": 0.1}})", "/materials/m/dielectric"},
      {R"({"dielectric": {"eta": {"nm": [400, 700], "value": [1.5, 1.4]}}})",
       "dielectric eta 0.000000 at 385 nm is outside [0.01, 100]"},
      {R"({"dielectric": {"eta": "BK8"}})", "/materials/m/dielectric/eta: unknown glass \"BK8\""},
      {R"({"dielectric": {"eta": {"sellmeier": {"B": [1.0], "C_um2": [0.01, 0.02]}}}})",
       "/materials/m/dielectric/eta/sellmeier: \"B\" and \"C_um2\" need the same number"},
      {R"({"dielectric": {"eta": {"sellmeier": {"B": [1.0], "C_um2": [0.3]}}}})",
       "/materials/m): dielectric eta nan at 385 nm is outside [0.01, 100]"},
      {R"({"dielectric": {"eta": {"cauchy": {"A": 1.5, "B_um2": -1}}}})",
       "/materials/m): dielectric eta -5."},
      {R"({"dielectric": {}, "passive": {"reflectance": 0.5}})",
       "/materials/m/dielectric: a dielectric or conductor has no \"passive\""},
      {R"({"dielectric": {}, "conductor": {}})", "not both"},
      {R"({"conductor": {"metal": "Pt"}})", "/materials/m/conductor/metal: unknown metal \"Pt\""},
      {R"({"conductor": {"metal": "Au", "roughness": 1.5}})", "/materials/m/conductor/roughness:"},
      {R"({"dielectric": {"roughness": -0.1}})", "/materials/m/dielectric/roughness:"},
      {R"({"dielectric": {"roughness": 0.1, "uroughness": 0.2}})",
       "/materials/m/dielectric/roughness: give"},
      {R"({"conductor": {"vroughness": "rough"}})", "/materials/m/conductor/vroughness:"},
      {R"({"dielectric": {"remap_roughness": 1}})", "/materials/m/dielectric/remap_roughness:"},
      {R"({"conductor": {"eta": 0.2}})", "/materials/m/conductor: \"eta\" without \"k\""},
      {R"({"conductor": {"metal": "Au", "k": 3}})", "not both"},
      {R"({"conductor": {"eta": {"nm": [500, 600], "value": [0.2, 0.3]}, "k": 3}})",
       "conductor eta 0.000000 at"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"eta": 0}})",
       "/materials/m/coat/eta: eta must lie in"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"thickness": -1}})",
       "/materials/m/coat/thickness:"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"uroughness": 0.1, "vroughness": 0.2}})",
       "/materials/m/coat: an anisotropic coat is not built"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"roughness": 1.5}})",
       "/materials/m/coat/roughness:"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"albedo": 0.5}})",
       "/materials/m/coat/albedo:"},
      {R"({"passive": {"reflectance": 0.5}, "coat": {"eta": 1.5, "thikness": 0.1}})",
       "/materials/m/coat"},
      {R"({"gloss": {"reflectance": 0.1}, "coat": {}})",
       "/materials/m/coat: a coated material has no \"gloss\""},
      {R"({"dielectric": {}, "coat": {}})", "/materials/m/coat: a dielectric takes no coat"},
      {R"({"passive": {"reflectance": 0.5}, "coat": 1.5})", "/materials/m/coat:"},
  };
  int k = 0;
  for (const auto& [material, message] : cases) {
    std::string file = scene_with("bad_specular_" + std::to_string(k++) + ".json", material);
    std::string error = error_of([&] { load_scene(file); });
    EXPECT_NE(error.find(message), std::string::npos) << material << "\n  gave: " << error;
  }
}

// Lean: the kernels are built with only the material kinds a scene's shapes use.
TEST(SpecularMaterial, KernelsCarryOnlyTheKindsTheSceneUses) {
  CommandResult glass = run_kasha("info " + source_path("scenes/furnace_glass.json"));
  ASSERT_EQ(glass.exit_code, 0) << glass.err;
  EXPECT_NE(glass.out.find("-D KASHA_DIELECTRIC=1"), std::string::npos) << glass.out;
  EXPECT_NE(glass.out.find("-D KASHA_CONDUCTOR=0"), std::string::npos) << glass.out;
  CommandResult plain = run_kasha("info " + source_path("scenes/cornell_box.json"));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("-D KASHA_DIELECTRIC=0"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("-D KASHA_CONDUCTOR=0"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("-D KASHA_COATED=0"), std::string::npos) << plain.out;
  const std::string coated = write_file("coated_info.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 40, "width": 8, "height": 8},
  "materials": {"m": {"passive": {"reflectance": 0.5}, "coat": {}}},
  "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m",
              "emission": 1}]})");
  CommandResult c = run_kasha("info " + coated);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("-D KASHA_COATED=1"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("coated yes"), std::string::npos) << c.out;
}

}  // namespace
