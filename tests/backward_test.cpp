// The backward integrator against the analytic fluorescent furnace (DESIGN §1), against a
// brute-force full-matrix path state, and for finiteness and convergence.
#include <gtest/gtest.h>

#include <cmath>

#include "render/furnace.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

struct FurnaceCase {
  const char* scene;
  std::array<double, 3> position, look_at;  // a second camera placement
};

void expect_furnace(const std::string& path, const RenderSettings& settings) {
  RenderResult r = render_scene(path, settings);
  Furnace f = analyze_furnace(r.scene);
  ASSERT_TRUE(f.qualifies) << f.why_not;
  expect_bins_match(r, f.radiance, 0.01, path);
}

void PrintTo(const FurnaceCase& c, std::ostream* os) {
  *os << c.scene;
}

class FurnaceTest : public ::testing::TestWithParam<FurnaceCase> {};

}  // namespace

TEST_P(FurnaceTest, EveryBinMatchesTheAnalyticValueFromTwoCameras) {
  const FurnaceCase& c = GetParam();
  std::string path = source_path(std::string("scenes/") + c.scene);
  RenderSettings settings;
  settings.passes = 8;
  settings.spp = 64;
  expect_furnace(path, settings);
  Camera moved;
  moved.position = c.position;
  moved.look_at = c.look_at;
  moved.width = 24;
  moved.height = 16;
  settings.camera = moved;
  expect_furnace(path, settings);
}

INSTANTIATE_TEST_SUITE_P(
    Backward, FurnaceTest,
    ::testing::Values(FurnaceCase{"furnace_passive.json", {-1.2, 0.8, 0.4}, {0, -1, 0}},
                      FurnaceCase{"furnace_fluorescent.json", {0.8, -0.8, 1.8}, {-1, 1, -1}},
                      FurnaceCase{"furnace_uv.json", {0.7, 0.7, 0.0}, {-1, 0, 1}},
                      FurnaceCase{"furnace_self_absorption.json", {-0.9, 0.9, 1.4}, {1, -1, -1}},
                      FurnaceCase{"furnace_mirror.json", {0.5, -0.5, 0.3}, {-1, 0, 0}}),
    [](const auto& info) {
      return std::string(info.param.scene).substr(8, std::string(info.param.scene).size() - 13);
    });

TEST(Backward, RankOneAlgebraMatchesTheFullMatrixReference) {
  // The rank-1 kernel against a test-only kernel that carries the full 3 × N matrix along each
  // path, with different seeds: on the Cornell box with the measured Post-it sphere (structure),
  // and in the self-absorbing furnace, where chains of fluorescent bounces carry much of the light.
  for (const char* scene : {"cornell_box.json", "furnace_self_absorption.json"}) {
    std::string path = source_path(std::string("scenes/") + scene);
    Camera cam = load_scene(path).camera;
    cam.width = cam.height = 16;
    RenderSettings s;
    s.camera = cam;
    s.spectral = false;
    s.passes = 32;
    s.spp = 64;
    RenderResult rank1 = render_scene(path, s);
    s.full_matrix = true;
    s.seed = 2;
    RenderResult full = render_scene(path, s);
    // Whole image and its four quadrants, X, Y and Z.
    std::vector<std::vector<size_t>> regions(5);
    for (size_t p = 0; p < 256; ++p) {
      regions[0].push_back(p);
      regions[1 + (p % 16 >= 8) + 2 * (p / 16 >= 8)].push_back(p);
    }
    for (const auto& region : regions) {
      BinStats a = pixel_statistics(rank1.image, false, region);
      BinStats d = difference_statistics(rank1.image, full.image, false, region);
      for (int k = 0; k < 3; ++k) {
        EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k])
            << scene << " row " << k << ": " << a.mean[k] << " vs " << a.mean[k] - d.mean[k];
        EXPECT_LT(d.standard_error[k], 0.015 * a.mean[k])
            << scene;  // tight enough to catch a 6 % error
      }
    }
  }
}

TEST(Backward, EveryScenePathIsFinite) {
  for (const char* scene :
       {"cornell_box.json", "torus.json", "furnace_passive.json", "furnace_fluorescent.json",
        "furnace_uv.json", "furnace_self_absorption.json", "furnace_mirror.json"}) {
    Camera cam = load_scene(source_path(std::string("scenes/") + scene)).camera;
    cam.width = 24;
    cam.height = 16;
    RenderSettings s;
    s.camera = cam;
    s.passes = 2;
    s.spp = 8;
    RenderResult r = render_scene(source_path(std::string("scenes/") + scene), s);
    EXPECT_EQ(r.rejected, 0) << scene;
    for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v) && v >= 0) << scene;
    for (float v : r.image.xyz) ASSERT_TRUE(std::isfinite(v)) << scene;
  }
}

TEST(Backward, ErrorFallsAsTheInverseSquareRootOfSamples) {
  // RMSE against the analytic furnace after 1, 2, 4, ... 64 passes: an unbiased estimator's
  // error falls as samples^(-1/2). The fit is over log–log points.
  std::string path = source_path("scenes/furnace_fluorescent.json");
  Scene scene = load_scene(path);
  Furnace f = analyze_furnace(scene);
  Image truth = furnace_image(scene, f.radiance, false);
  RenderSettings s;
  s.spectral = false;
  s.spp = 2;
  std::vector<double> x, y;
  for (int passes : {1, 2, 4, 8, 16, 32, 64}) {
    s.passes = passes;
    RenderResult r = render_scene(path, s);
    double se = 0;
    for (size_t i = 0; i < truth.xyz.size(); ++i) se += std::pow(r.image.xyz[i] - truth.xyz[i], 2);
    x.push_back(std::log(passes));
    y.push_back(std::log(std::sqrt(se / truth.xyz.size())));
  }
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / x.size(), my += y[i] / y.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i)
    sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  double slope = sxy / sxx;
  std::printf("  RMSE slope over samples: %.3f\n", slope);
  EXPECT_NEAR(slope, -0.5, 0.08);
}
