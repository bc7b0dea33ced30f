// Photon mapping against the analytic furnace (converging with passes), against backward on the
// Cornell box, and the compactness of what it stores.
#include <gtest/gtest.h>

#include <cmath>

#include "render/device_scene.h"
#include "render/furnace.h"
#include "render/photon_map_integrator.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// Largest relative error over the bins that carry light, of the image mean against L.
double worst_bin_error(const Image& img, const std::vector<double>& truth) {
  BinStats s = pixel_statistics(img, true);
  double peak = *std::max_element(truth.begin(), truth.end()), worst = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    if (truth[i] >= 1e-3 * peak) worst = std::max(worst, std::abs(s.mean[i] - truth[i]) / truth[i]);
  return worst;
}

// Per-pixel relative RMS error over the bins that carry light: noise and bias together.
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

}  // namespace

class PhotonFurnace : public ::testing::TestWithParam<const char*> {};

TEST_P(PhotonFurnace, ConvergesToTheAnalyticValue) {
  std::string path = source_path(std::string("scenes/") + GetParam());
  Scene scene = load_scene(path);
  Furnace f = analyze_furnace(scene);
  ASSERT_TRUE(f.qualifies) << f.why_not;
  RenderSettings s;
  s.integrator = "photon";
  s.photons = 1 << 15;
  s.passes = 40;
  std::vector<double> rms;  // per-pixel relative RMS error after 1, 4, 16, 40 passes
  s.after_pass = [&](int pass, const Image& img) {
    if (pass == 1 || pass == 4 || pass == 16 || pass == 40)
      rms.push_back(pixel_rms_error(img, f.radiance));
  };
  RenderResult r = render_scene(path, s);
  ASSERT_EQ(rms.size(), 4u);
  EXPECT_LT(rms[1], rms[0]) << "the per-bin error falls with passes";
  EXPECT_LT(rms[2], rms[1]);
  EXPECT_LT(rms[3], rms[2]);
  double worst = worst_bin_error(r.image, f.radiance);
  std::printf(
      "  per-pixel relative RMS error after 1/4/16/40 passes: %.4f %.4f %.4f %.4f; worst bin "
      "%.4f\n",
      rms[0], rms[1], rms[2], rms[3], worst);
  EXPECT_LT(worst, 0.02);
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v));
}

INSTANTIATE_TEST_SUITE_P(Photon, PhotonFurnace, ::testing::ValuesIn(kFurnaceScenes),
                         furnace_test_name);

TEST(Photon, AgreesWithBackwardOnTheCornellBox) {
  ComparedRenders pair = render_against_backward("cornell_box.json", "photon", 24, 1 << 17);
  const RenderResult &pm = pair.tested, &bwd = pair.backward;

  std::map<std::string, std::vector<size_t>> regions = primary_hit_regions(pm.scene, pair.camera);
  ASSERT_EQ(regions.size(), 5u);
  for (const auto& [name, pixels] : regions) {
    BinStats p = pixel_statistics(pm.image, false, pixels),
             b = pixel_statistics(bwd.image, false, pixels);
    std::printf("  %-8s photon/backward - 1: X %+.2f %%, Y %+.2f %%, Z %+.2f %%\n", name.c_str(),
                100 * (p.mean[0] / b.mean[0] - 1), 100 * (p.mean[1] / b.mean[1] - 1),
                100 * (p.mean[2] / b.mean[2] - 1));
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(std::abs(p.mean[c] - b.mean[c]), 0.03 * b.mean[c])
          << name << " row " << c << ": photon " << p.mean[c] << " backward " << b.mean[c];
  }
}

TEST(Photon, DiscCoverageRemovesTheEdgeBias) {
  // In a box furnace the gather discs of pixels near the box's edges hang over them; without the
  // coverage correction those pixels, and the image mean, come out dark.
  std::string path = source_path("scenes/furnace_fluorescent.json");
  Scene scene = load_scene(path);
  Furnace f = analyze_furnace(scene);
  RenderSettings s;
  s.integrator = "photon";
  s.photons = 1 << 15;
  s.passes = 40;
  s.edge_correction = true;
  double corrected = worst_bin_error(render_scene(path, s).image, f.radiance);
  s.edge_correction = false;
  double plain = worst_bin_error(render_scene(path, s).image, f.radiance);
  std::printf("  worst bin: %.4f with the correction, %.4f without\n", corrected, plain);
  EXPECT_LT(corrected, 0.004);
  EXPECT_GT(plain, 2 * corrected);
}

TEST(Photon, NonFluorescentScenesCarryNoRankOneFactor) {
  // Torus: no fluorescence; its kernels are built without it and its visible points hold d alone.
  Scene plain = load_scene(source_path("scenes/torus.json"));
  EXPECT_EQ(scene_defines(plain, false).at("KASHA_FLUORESCENCE"), "0");
  const size_t N = plain.grid.bins;
  EXPECT_EQ(visible_point_bytes(plain, false), (8 + N) * sizeof(float));
  Camera cam = plain.camera;
  cam.width = 8;
  cam.height = 4;
  RenderSettings s;
  s.integrator = "photon";
  s.camera = cam;
  s.passes = 1;
  s.photons = 1 << 12;
  s.spectral = false;
  RenderResult r = render_scene(source_path("scenes/torus.json"), s);
  EXPECT_EQ(r.visible_point_buffer_bytes, 32 * (8 + N) * sizeof(float));
  // A fluorescent scene's visible point: 2N + R values of factor and 8 of geometry.
  Scene fluorescent = load_scene(source_path("scenes/cornell_box.json"));
  EXPECT_EQ(scene_defines(fluorescent, false).at("KASHA_FLUORESCENCE"), "1");
  const size_t M = fluorescent.grid.bins;
  EXPECT_EQ(visible_point_bytes(fluorescent, false), (8 + 2 * M + 3) * sizeof(float));
  EXPECT_EQ(visible_point_bytes(fluorescent, true), (8 + 3 * M) * sizeof(float));
  EXPECT_EQ(photon_record_bytes(fluorescent), (6 + M) * sizeof(float));
}

TEST(Photon, RadiiThatCatchNoPhotonStayFinite) {
  // A tiny fixed radius: most visible points find nothing; the estimate stays finite and falls
  // back to what was seen directly.
  RenderSettings s;
  s.integrator = "photon";
  s.passes = 3;
  s.photons = 1 << 10;
  s.radius = 1e-6;
  RenderResult r = render_scene(source_path("scenes/furnace_fluorescent.json"), s);
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v) && v >= 0);
}
