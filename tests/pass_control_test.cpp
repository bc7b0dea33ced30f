// Passes cut short between launches (render/pass_control.h, render/launch_pacer.h): a deadline
// that has passed stops every pass after its first launch, and what the pass did still estimates
// the image without bias — backward with per-pixel sample counts, forward and photon mapping with
// the photons traced scaled up to the pass's count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/integrator_registry.h"
#include "render/launch_pacer.h"
#include "render/progressive_render.h"
#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

// The progress line's time left counts the pass in flight: one long pass half done after 10 s
// has 10 s left (not 0), a pass whose integrator reports no fraction is estimated from the passes
// before it, and the first such pass says nothing rather than a wrong 0.
TEST(ProgressLine, TimeLeftCountsThePassInFlight) {
  const StopCondition one_pass{0, 1}, four_passes{0, 4}, both{30, 4};
  EXPECT_DOUBLE_EQ(seconds_left(one_pass, 0, 0, 10, 0.5), 10);
  EXPECT_DOUBLE_EQ(seconds_left(one_pass, 0, 0, 9, 0.9), 1);
  EXPECT_LT(seconds_left(one_pass, 0, 0, 10, 0), 0);  // unknown yet
  // Two passes of 5 s done, 2 s into the third, no fraction: 3 s of it and 5 s of the last.
  EXPECT_DOUBLE_EQ(seconds_left(four_passes, 2, 10, 2, 0), 8);
  // A pass running longer than the others: at least the passes after it.
  EXPECT_DOUBLE_EQ(seconds_left(four_passes, 2, 10, 7, 0), 5);
  // Between passes: the remaining passes at the mean so far.
  EXPECT_DOUBLE_EQ(seconds_left(four_passes, 1, 5, 0, 0), 15);
  // --time and --passes: whichever ends first.
  EXPECT_DOUBLE_EQ(seconds_left(both, 2, 10, 2, 0), 8);
  EXPECT_DOUBLE_EQ(seconds_left(StopCondition{12, 4}, 2, 10, 1, 0), 1);
  EXPECT_DOUBLE_EQ(seconds_left(StopCondition{12, 0}, 0, 0, 5, 0.1), 7);
}

TEST(LaunchPacer, StartsSmallGrowsAtMostFourfoldAndFitsTheTarget) {
  LaunchPacer pacer(0.2, 100);
  EXPECT_EQ(pacer.next(1000000), 100u);
  EXPECT_EQ(pacer.next(30), 30u);  // never more than what remains
  pacer.record(100, 0.001);        // fast: grows, but fourfold at most
  EXPECT_EQ(pacer.next(1000000), 400u);
  pacer.record(400, 0.8);  // 2 ms per item: 100 fit in 0.2 s
  EXPECT_EQ(pacer.next(1000000), 100u);
  pacer.record(100, 100.0);  // one launch far too long: at least one item still
  EXPECT_EQ(pacer.next(1000000), 1u);
  pacer.record(5, 0.0);  // a launch too short to time: fourfold growth
  EXPECT_EQ(pacer.next(1000000), 20u);
}

class CutShortPasses : public ::testing::TestWithParam<std::string> {};

TEST_P(CutShortPasses, StillEstimateTheFurnace) {
  const std::string integrator = GetParam();
  const IntegratorInfo& info = IntegratorRegistry::find(integrator);
  const std::string path = source_path("scenes/furnace_fluorescent.json");
  Scene scene = load_scene(path);
  Furnace f = analyze_furnace(scene);
  ASSERT_TRUE(f.qualifies) << f.why_not;
  RenderSettings s;
  s.integrator = integrator;
  s.spectral = true;
  Camera c = scene.camera;
  c.width = c.height = 64;  // more pixels than the first launch: it covers some of them
  // vcm, bpt and ppm run their first iteration whole (it compiles their kernels), by then their
  // camera launches have grown to thousands of pixels: more pixels than those.
  const bool iterations = integrator == "vcm" || integrator == "bpt" || integrator == "ppm";
  if (iterations) c.width = c.height = 256;
  s.camera = c;
  // Work for several launches a pass: the pacer's first launches are small and it grows them at
  // most fourfold, so the first passes stop early and later ones run whole. A cut-short pass
  // weighs as much as a whole one in forward's and photon mapping's mean, so a wrong scale-up
  // would show as a bias of its share of the passes. (vcm, bpt, ppm: their own camera paths a
  // pixel, the 256² image being the work.)
  s.integrator_settings.spp = iterations ? 0 : 64;
  s.integrator_settings.photons = 1 << 15;
  s.control.deadline = PassControl::Clock::time_point{};  // long past: one launch a pass
  if (info.traits.unbiased) {
    s.passes = 200;
    s.until = [&](int pass, const Image& img) {
      BinStats st = pixel_statistics(img, true);
      double worst = 0;
      for (size_t i = 0; i < f.radiance.size(); ++i)
        if (f.radiance[i] > 1e-3) worst = std::max(worst, st.standard_error[i] / f.radiance[i]);
      return pass >= 12 && worst < 0.003;
    };
  } else {
    s.passes = 24;
  }
  RenderResult r = render_scene(path, s);
  std::printf("  %s: %d passes worth %.3f whole ones\n", integrator.c_str(), r.passes,
              r.work_passes);
  // ppm's camera pass (a merge a pixel, after its first iteration) fits one launch here: no
  // deadline falls inside it, and its iterations run whole.
  if (integrator != "ppm") {
    EXPECT_LT(r.work_passes, r.passes - 1.5) << "the first passes stop after their first launch";
  }
  EXPECT_GT(r.work_passes, 0.0);
  expect_bins_match(r, f.radiance, info.traits.unbiased ? 0.01 : 0.03, integrator + " cut short",
                    info.traits.unbiased);
}

INSTANTIATE_TEST_SUITE_P(Registry, CutShortPasses,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });
