// Every physical integrator in the registry against the analytic fluorescent furnace
// (docs/design.md#the-fluorescent-furnace), in every furnace scene, on the default 10 nm grid (from
// two cameras) and on a 1 nm grid over 300–780 nm (480 bins). A new integrator is tested here by
// its registry line alone: its traits say whether it is unbiased (its image mean within 4 standard
// errors and 1 % of the truth, with passes until the standard error is 0.2 %) or consistent (within
// 2 % after a fixed number of passes, with the per-pixel error falling over them), and whether it
// sees ideal mirrors from the camera (light tracing cannot: it estimates (1 − g)·L in a mirror
// furnace).
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

struct FurnaceCase {
  std::string integrator, scene;
  bool fine_grid;  // 1 nm bins over 300–780 nm
};

void PrintTo(const FurnaceCase& c, std::ostream* os) {
  *os << c.integrator << " in " << c.scene << (c.fine_grid ? " at 1 nm" : " at 10 nm");
}

std::vector<FurnaceCase> all_cases() {
  std::vector<FurnaceCase> cases;
  for (const std::string& integrator : IntegratorRegistry::names(true))
    for (const char* scene : kFurnaceScenes)
      for (bool fine : {false, true}) cases.push_back({integrator, scene, fine});
  return cases;
}

// A second camera placement per furnace: another position, direction and aspect.
Camera second_camera(const std::string& scene) {
  static const std::map<std::string, std::pair<std::array<double, 3>, std::array<double, 3>>>
      placements = {{"furnace_passive.json", {{-1.2, 0.8, 0.4}, {0, -1, 0}}},
                    {"furnace_fluorescent.json", {{0.8, -0.8, 1.8}, {-1, 1, -1}}},
                    {"furnace_uv.json", {{0.7, 0.7, 0.0}, {-1, 0, 1}}},
                    {"furnace_self_absorption.json", {{-0.9, 0.9, 1.4}, {1, -1, -1}}},
                    {"furnace_mirror.json", {{0.5, -0.5, 0.3}, {-1, 0, 0}}}};
  Camera c;
  c.position = placements.at(scene).first;
  c.look_at = placements.at(scene).second;
  c.width = 24;
  c.height = 16;
  return c;
}

// The largest standard error of the image mean, relative to the truth, over the lit bins.
double worst_relative_error_bar(const Image& image, const std::vector<double>& truth) {
  BinStats s = pixel_statistics(image, true);
  double peak = *std::max_element(truth.begin(), truth.end()), worst = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    if (truth[i] >= 1e-3 * peak) worst = std::max(worst, s.standard_error[i] / truth[i]);
  return worst;
}

// Per-pixel relative RMS error over the lit bins: noise and bias together.
double pixel_rms_error(const Image& img, const std::vector<double>& truth) {
  double peak = *std::max_element(truth.begin(), truth.end()), sum = 0;
  size_t n = 0, N = truth.size();
  for (size_t p = 0; p < img.pixels(); ++p)
    for (size_t i = 0; i < N; ++i) {
      if (truth[i] < 1e-3 * peak) continue;
      double e = (img.spectral[p * N + i] - truth[i]) / truth[i];
      sum += e * e;
      ++n;
    }
  return std::sqrt(sum / n);
}

class IntegratorFurnace : public ::testing::TestWithParam<FurnaceCase> {
 protected:
  void check(const std::optional<Camera>& camera) {
    const FurnaceCase& c = GetParam();
    const IntegratorInfo& info = IntegratorRegistry::find(c.integrator);
    const std::string path = source_path("scenes/" + c.scene);
    RenderSettings s;
    s.integrator = c.integrator;
    s.camera = camera;
    if (c.fine_grid) s.grid = GridRequest{300, 780, 1};
    s.integrator_settings.spp = c.fine_grid ? 4 : 16;
    s.integrator_settings.photons = c.fine_grid ? 1 << 13 : 1 << 15;
    // ppm, merges alone, takes direct light from its photons too: its default 2^16.
    if (c.integrator == "ppm") s.integrator_settings.photons = 1 << 16;
    Scene scene = load_scene(path, s.grid);
    if (c.fine_grid) {
      ASSERT_EQ(scene.grid.bins, 480);
    }
    Furnace f = analyze_furnace(scene);
    ASSERT_TRUE(f.qualifies) << f.why_not;
    std::vector<double> truth = f.radiance;
    if (!info.traits.sees_camera_mirrors) {
      const Material& m = scene.materials[scene.shapes.front().material];
      if (m.gloss && m.gloss->mirror)
        for (double& v : truth) v *= 1 - m.gloss_reflectance();
    }

    std::vector<double>
        rms;  // consistent integrators: per-pixel error after 1, 4, 16 passes and at the end
    int passes = 0;
    if (info.traits.unbiased) {
      // Passes until the image mean's standard error is 0.2 % in every lit bin (at most 200).
      s.passes = 200;
      s.until = [&](int pass, const Image& img) {
        passes = pass;
        return pass >= 4 && worst_relative_error_bar(img, truth) < 0.002;
      };
    } else {
      s.passes = c.fine_grid ? 24 : 40;
      s.after_pass = [&](int pass, const Image& img) {
        passes = pass;
        if (pass == 1 || pass == 4 || pass == 16 || pass == s.passes)
          rms.push_back(pixel_rms_error(img, truth));
      };
    }
    RenderResult r = render_scene(path, s);
    std::printf("  %s, %s%s: %d passes, worst error bar %.4f\n", c.integrator.c_str(),
                c.scene.c_str(), camera ? " (second camera)" : "", passes,
                worst_relative_error_bar(r.image, truth));
    expect_bins_match(r, truth, info.traits.unbiased ? 0.01 : 0.02, c.integrator + " " + c.scene,
                      info.traits.unbiased);
    if (!info.traits.unbiased) {
      ASSERT_EQ(rms.size(), 4u);
      for (size_t k = 1; k < rms.size(); ++k)
        EXPECT_LT(rms[k], rms[k - 1]) << "the per-pixel error falls with passes";
    }
  }
};

TEST_P(IntegratorFurnace, EveryBinMatchesTheAnalyticValue) {
  check(std::nullopt);
  if (!GetParam().fine_grid) check(second_camera(GetParam().scene));
}

INSTANTIATE_TEST_SUITE_P(Registry, IntegratorFurnace, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           const FurnaceCase& c = info.param;
                           return c.integrator + "_" + c.scene.substr(8, c.scene.size() - 13) +
                                  (c.fine_grid ? "_1nm" : "_10nm");
                         });

}  // namespace
