// Photon mapping's edge correction, the compactness of what it stores, and radii that catch
// nothing (its furnace and agreement tests are in integrator_*_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/photon/photon_records.h"
#include "render/device_scene.h"
#include "render_support.h"
#include "study/furnace.h"
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

}  // namespace

TEST(Photon, DiscCoverageRemovesTheEdgeBias) {
  // In a box furnace the gather discs of pixels near the box's edges hang over them; without the
  // coverage correction those pixels, and the image mean, come out dark.
  std::string path = source_path("scenes/furnace_fluorescent.json");
  Scene scene = load_scene(path);
  Furnace f = analyze_furnace(scene);
  RenderSettings s;
  s.integrator = "photon";
  s.integrator_settings.photons = 1 << 15;
  s.passes = 40;
  s.integrator_settings.edge_correction = true;
  double corrected = worst_bin_error(render_scene(path, s).image, f.radiance);
  s.integrator_settings.edge_correction = false;
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
  s.integrator_settings.photons = 1 << 12;
  s.spectral = false;
  RenderResult r = render_scene(source_path("scenes/torus.json"), s);
  EXPECT_EQ(r.device_buffers.at("visible points"), 32 * (8 + N) * sizeof(float));
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
  s.integrator_settings.photons = 1 << 10;
  s.integrator_settings.radius = 1e-6;
  RenderResult r = render_scene(source_path("scenes/furnace_fluorescent.json"), s);
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v) && v >= 0);
}
