// The forward integrator (light tracing) against the analytic furnace, against the backward
// integrator on the Cornell box, and its power bookkeeping.
#include <gtest/gtest.h>

#include <cmath>

#include "render/furnace.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// Light tracing cannot see an ideal mirror from a pinhole: it estimates everything but the
// mirror-reflected part g·L of what the camera sees, i.e. (1 − g)·L in a furnace.
std::vector<double> forward_furnace_value(const Scene& scene, const Furnace& f) {
  double g = scene.materials[scene.shapes.front().material].gloss_reflectance();
  bool mirror = g > 0 && scene.materials[scene.shapes.front().material].gloss->mirror;
  std::vector<double> v = f.radiance;
  if (mirror)
    for (double& x : v) x *= 1 - g;
  return v;
}

}  // namespace

class ForwardFurnace : public ::testing::TestWithParam<const char*> {};

TEST_P(ForwardFurnace, EveryBinMatchesTheAnalyticValue) {
  std::string path = source_path(std::string("scenes/") + GetParam());
  RenderSettings s;
  s.integrator = "forward";
  s.passes = 12;
  s.photons = 1 << 18;
  RenderResult r = render_scene(path, s);
  Furnace f = analyze_furnace(r.scene);
  ASSERT_TRUE(f.qualifies) << f.why_not;
  expect_bins_match(r, forward_furnace_value(r.scene, f), 0.01, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Forward, ForwardFurnace, ::testing::ValuesIn(kFurnaceScenes),
                         furnace_test_name);

TEST(Forward, PowerIsConservedInAClosedScene) {
  // Photons cut after 3 bounces: absorbed + still in flight = emitted, and nothing escapes.
  RenderSettings s;
  s.integrator = "forward";
  s.passes = 2;
  s.photons = 100000;
  s.max_depth = 3;
  for (const char* scene : {"furnace_fluorescent.json", "furnace_mirror.json", "furnace_uv.json"}) {
    RenderResult r = render_scene(source_path(std::string("scenes/") + scene), s);
    const PhotonLedger& l = r.ledger;
    EXPECT_NEAR(l.absorbed + l.in_flight, l.emitted, 1e-5 * l.emitted) << scene;
    EXPECT_EQ(l.escaped, 0) << scene;
    EXPECT_GT(l.in_flight, 0.05 * l.emitted) << scene;  // the cut leaves photons in flight
    // A pass's photons carry the lights' total power.
    KernelSceneData data(r.scene);
    EXPECT_NEAR(l.emitted, 2 * data.total_power, 1e-4 * data.total_power) << scene;
  }
}

TEST(Forward, ImageDoesNotDependOnHowWorkIsSplit) {
  // The same photons spread over work items of 64, 7 and 1 photons: each photon's random numbers
  // depend on its index only and the fixed-point film adds exactly, so the images are identical.
  RenderSettings a;
  a.integrator = "forward";
  a.spectral = false;
  a.passes = 1;
  a.photons = 40000;
  std::vector<float> reference;
  for (int per_item : {64, 7, 1}) {
    a.photons_per_item = per_item;
    RenderResult r = render_scene(source_path("scenes/furnace_fluorescent.json"), a);
    if (reference.empty()) reference = r.image.xyz;
    EXPECT_EQ(r.image.xyz, reference) << per_item << " photons per work item";
  }
}

TEST(Forward, AgreesWithBackwardOnTheCornellBox) {
  ComparedRenders pair = render_against_backward("cornell_box.json", "forward", 24, 1 << 19);
  const RenderResult &fwd = pair.tested, &bwd = pair.backward;
  const Camera& cam = pair.camera;

  // Regions: the pixels whose centre sees each material (and the lamp), by Embree.
  std::map<std::string, std::vector<size_t>> regions = primary_hit_regions(fwd.scene, cam);
  EXPECT_EQ(regions.size(), 5u);  // white, red, green, the lamp, the Post-it sphere
  for (const auto& [name, pixels] : regions) {
    BinStats f = pixel_statistics(fwd.image, false, pixels);
    BinStats d = difference_statistics(fwd.image, bwd.image, false, pixels);
    for (int c = 0; c < 3; ++c) {
      double b = f.mean[c] - d.mean[c];
      EXPECT_LT(std::abs(d.mean[c]), 0.02 * b)
          << name << " row " << c << ": forward " << f.mean[c] << " backward " << b;
      EXPECT_LT(std::abs(d.mean[c]), 4 * d.standard_error[c]) << name << " row " << c;
    }
  }
  // The images within noise: in each 6 × 6 block, the mean difference within 5 standard errors.
  for (int by = 0; by < 8; ++by)
    for (int bx = 0; bx < 8; ++bx) {
      std::vector<size_t> block;
      for (int y = 6 * by; y < 6 * by + 6; ++y)
        for (int x = 6 * bx; x < 6 * bx + 6; ++x)
          block.push_back(static_cast<size_t>(y) * cam.width + x);
      BinStats d = difference_statistics(fwd.image, bwd.image, false, block);
      for (int c = 0; c < 3; ++c)
        EXPECT_LE(std::abs(d.mean[c]), 5 * d.standard_error[c])
            << "block " << bx << "," << by << " row " << c;
    }
}
