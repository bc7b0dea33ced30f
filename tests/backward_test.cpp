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
  BinStats s = pixel_statistics(r.image, true);
  double peak = *std::max_element(f.radiance.begin(), f.radiance.end());
  int checked = 0;
  for (size_t i = 0; i < f.radiance.size(); ++i) {
    double truth = f.radiance[i];
    // Bins with (next to) no light: the estimate must be as small.
    if (truth < 1e-3 * peak) {
      EXPECT_LT(s.mean[i], 2e-3 * peak + 4 * s.standard_error[i]) << path << " bin " << i;
      continue;
    }
    ++checked;
    EXPECT_LT(std::abs(s.mean[i] - truth), 4 * s.standard_error[i] + 1e-6 * truth)
        << path << " bin " << r.scene.grid.center(i) << " nm: " << s.mean[i] << " vs " << truth << " ± "
        << s.standard_error[i];
    EXPECT_LT(std::abs(s.mean[i] - truth), 0.01 * truth) << path << " bin " << r.scene.grid.center(i) << " nm";
  }
  EXPECT_GT(checked, 3);
  EXPECT_EQ(r.rejected, 0);
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v));
}

void PrintTo(const FurnaceCase& c, std::ostream* os) { *os << c.scene; }

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
    [](const auto& info) { return std::string(info.param.scene).substr(8, std::string(info.param.scene).size() - 13); });
