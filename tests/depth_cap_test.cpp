// --max-depth N, pbrt-v4's maxdepth, in every physical integrator against the analytic furnace:
// inside a closed emitting enclosure whose wall scatters by M (diag(g + ρ) + ê aᵀ: gloss, passive
// and fluorescent parts), a path of k scattering vertices brings Mᵏ Le, so the cap N sees
// Σ_{k=0..N} Mᵏ Le — Le (N = 0), Le + M Le (1, direct light), and so on; each bin is checked
// against it within the estimator's own standard error (unbiased integrators) or a tolerance
// (consistent ones). Also pbrt-v4's default when a scene's Integrator gives none, and the
// importer's reading of it.
#include "render/depth_cap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/integrator_registry.h"
#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// Σ_{k=0..cap} Mᵏ Le per bin for the furnace's one material and emission.
std::vector<double> capped_furnace(const Scene& scene, int cap) {
  const Material& m = scene.materials[scene.shapes.front().material];
  const std::vector<double>& le = scene.emitters.at(scene.shapes.front().emitter).per_bin;
  std::vector<double> sum = le, term = le;
  for (int k = 1; k <= cap; ++k) {
    double absorbed = 0;  // aᵀ term: what the fluorescent part takes in
    for (size_t i = 0; i < m.a.size(); ++i) absorbed += m.a[i] * term[i];
    for (size_t i = 0; i < term.size(); ++i) {
      const double kept = m.gloss_reflectance() + (m.rho.empty() ? 0.0 : m.rho[i]);
      term[i] = kept * term[i] + (m.fluorescent() ? m.e_hat[i] * absorbed : 0.0);
      sum[i] += term[i];
    }
  }
  return sum;
}

struct CapCase {
  std::string integrator, scene;
  int cap;
};

void PrintTo(const CapCase& c, std::ostream* os) {
  *os << c.integrator << " in " << c.scene << " at --max-depth " << c.cap;
}

std::vector<CapCase> all_cases() {
  std::vector<CapCase> cases;
  // The mirror furnace where the integrator sees camera mirrors: a mirror bounce counts too, and
  // photon mapping's visible points lie behind camera bounces, which its gather must count.
  for (const std::string& integrator : IntegratorRegistry::names(true))
    for (const char* scene :
         {"furnace_passive.json", "furnace_fluorescent.json", "furnace_mirror.json"})
      if (IntegratorRegistry::find(integrator).traits.sees_camera_mirrors ||
          std::string(scene) != "furnace_mirror.json")
        for (int cap : {0, 1, 3}) cases.push_back({integrator, scene, cap});
  return cases;
}

class DepthCapFurnace : public ::testing::TestWithParam<CapCase> {};

}  // namespace

// The series' operator is the furnace's: summed far enough, it is analyze_furnace's solution.
TEST(DepthCapFurnace, TheSeriesSumsToTheUncappedFurnace) {
  for (const char* name :
       {"furnace_passive.json", "furnace_fluorescent.json", "furnace_mirror.json"}) {
    const Scene scene = load_scene(source_path(std::string("scenes/") + name));
    const std::vector<double> whole = analyze_furnace(scene).radiance,
                              series = capped_furnace(scene, 400);
    for (size_t i = 0; i < whole.size(); ++i) EXPECT_NEAR(series[i], whole[i], 1e-9 * whole[i]);
    EXPECT_LT(capped_furnace(scene, 1)[20], 0.9 * whole[20]) << "a cap that takes light away";
  }
}

// Renders the furnace case (photon mapping gathering as `gather` says) and checks every bin.
void expect_capped_furnace(const CapCase& c, Gather gather = Gather::automatic) {
  const IntegratorInfo& info = IntegratorRegistry::find(c.integrator);
  const std::string path = source_path("scenes/" + c.scene);
  RenderSettings s;
  s.integrator = c.integrator;
  s.integrator_settings.max_depth = c.cap;
  s.integrator_settings.seed = 7;
  s.integrator_settings.spp = 4;
  s.integrator_settings.photons = c.integrator == "ppm" ? 1 << 15 : 1 << 13;
  s.integrator_settings.gather = gather;
  const std::vector<double> truth = capped_furnace(load_scene(path), c.cap);
  if (info.traits.unbiased) {
    // Passes until the image mean's standard error is 0.3 % in every lit bin (at most 64).
    s.passes = 64;
    s.until = [&](int pass, const Image& img) {
      const BinStats b = pixel_statistics(img, true);
      const double peak = *std::max_element(truth.begin(), truth.end());
      double worst = 0;
      for (size_t i = 0; i < truth.size(); ++i)
        if (truth[i] >= 1e-3 * peak) worst = std::max(worst, b.standard_error[i] / truth[i]);
      return pass >= 2 && worst < 0.003;
    };
  } else {
    s.passes = 12;
  }
  const RenderResult r = render_scene(path, s);
  std::printf("  %s, %s, --max-depth %d: %d passes\n", c.integrator.c_str(), c.scene.c_str(), c.cap,
              r.passes);
  expect_bins_match(r, truth, info.traits.unbiased ? 0.015 : 0.03,
                    c.integrator + " " + c.scene + " cap " + std::to_string(c.cap),
                    info.traits.unbiased);
}

TEST_P(DepthCapFurnace, EveryBinMatchesTheCappedSeries) {
  expect_capped_furnace(GetParam());
}

// Photon mapping's host gather (--gather host) applies the cap as the device's does.
TEST(DepthCapFurnace, PhotonMappingsHostGatherKeepsTheCap) {
  for (int cap : {1, 3})
    expect_capped_furnace({"photon", "furnace_mirror.json", cap}, Gather::host);
}

INSTANTIATE_TEST_SUITE_P(Registry, DepthCapFurnace, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           const CapCase& c = info.param;
                           return c.integrator + "_" + c.scene.substr(8, c.scene.size() - 13) +
                                  "_cap" + std::to_string(c.cap);
                         });

// The Integrator's maxdepth, pbrt-v4's default 5 where it gives none or the file has no
// Integrator, none for an integrator without one; `--max-depth scene` takes it, and refuses a
// scene that names none.
TEST(DepthCap, TheSceneCapIsThePbrtIntegratorsMaxdepth) {
  const std::string camera =
      "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
      "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n";
  const std::string world =
      "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
      "\"integer indices\" [0 1 2  0 2 3]\n";
  const std::vector<std::pair<std::string, std::optional<int>>> cases = {
      {"Integrator \"volpath\" \"integer maxdepth\" [65]\n", 65},
      {"Integrator \"bdpt\" \"integer maxdepth\" 0\n", 0},
      {"Integrator \"path\"\n", 5},
      {"", 5},
      {"Integrator \"ambientocclusion\"\n", std::nullopt}};
  IntegratorSettings from_scene;
  from_scene.max_depth = IntegratorSettings::kSceneDepthCap;
  for (const auto& [integrator, depth] : cases) {
    const Scene scene = load_scene(write_file("cap.pbrt", camera + integrator + world));
    EXPECT_EQ(scene.max_depth, depth) << integrator;
    if (depth) {
      EXPECT_EQ(depth_cap(from_scene, scene), *depth) << integrator;
    } else {
      EXPECT_NE(error_of([&] {
                  depth_cap(from_scene, scene);
                }).find("--max-depth: scene: " + scene.file + " names no maxdepth"),
                std::string::npos);
    }
  }
  IntegratorSettings given;
  given.max_depth = 2;
  EXPECT_EQ(depth_cap(given, load_scene(source_path("scenes/furnace_passive.json"))), 2);
  EXPECT_EQ(depth_cap(IntegratorSettings{}, load_scene(source_path("scenes/furnace_passive.json"))),
            IntegratorSettings::kNoDepthCap);
}

// The warning says what is used; `kasha render --max-depth scene` on a pbrt-v4 scene renders.
TEST(DepthCap, RenderTakesTheScenesMaxdepth) {
  const std::string file =
      write_file("s.pbrt",
                 "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
                 "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
                 "Integrator \"volpath\" \"integer maxdepth\" [3]\nWorldBegin\n"
                 "AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n"
                 "Shape \"trianglemesh\" \"point3 P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "
                 "\"integer indices\" [0 1 2  0 2 3]\n");
  const std::string out = (scratch_dir() / "s.exr").string();
  const CommandResult r =
      run_kasha("render " + file + " --max-depth scene --spp 1 --passes 1 -o " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(file + ":4: Integrator \"volpath\" is ignored"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("its maxdepth 3 is what --max-depth scene uses"), std::string::npos)
      << r.err;
}
