// Photon mapping's device gather against nanoflann's, the compactness of what it stores, and radii
// that catch nothing (its furnace and agreement tests are in integrator_*_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/photon/photon_records.h"
#include "render/device_scene.h"
#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Photon, DeviceGatherEqualsNanoflannGather) {
  // The same seed gives the same visible points and photons: the hashed grid's gather on the
  // device must find the photons nanoflann's kd-tree finds on the host, with the same flux to
  // rounding. Found counts set the next pass's radii, so one photon more or less anywhere moves
  // that pixel's later passes far beyond rounding. Fluorescent (rank-1 factors) and not, XYZ
  // and spectral films; small stores so passes gather in several batches.
  struct Case {
    const char* scene;
    bool spectral;
  };
  for (Case c : {Case{"scenes/cornell_box.json", false}, Case{"scenes/cornell_box.json", true},
                 Case{"scenes/torus.json", false}}) {
    SCOPED_TRACE(std::string(c.scene) + (c.spectral ? ", spectral" : ", XYZ"));
    Scene scene = load_scene(source_path(c.scene));
    Camera cam = scene.camera;
    cam.width = 48;
    cam.height = 48;
    RenderSettings s;
    s.integrator = "photon";
    s.camera = cam;
    s.spectral = c.spectral;
    s.passes = 3;
    s.integrator_settings.photons = 1 << 14;
    s.integrator_settings.memory = 40000 * photon_record_bytes(scene);  // several batches a pass
    s.integrator_settings.gather = "device";
    Image device = render_scene(source_path(c.scene), s).image;
    s.integrator_settings.gather = "host";
    Image host = render_scene(source_path(c.scene), s).image;
    ASSERT_EQ(device.xyz.size(), host.xyz.size());
    double peak = 0, worst = 0, total = 0;
    for (float v : host.xyz) peak = std::max(peak, std::abs(double(v)));
    for (size_t i = 0; i < host.xyz.size(); ++i) {
      worst = std::max(worst, std::abs(double(device.xyz[i]) - host.xyz[i]) /
                                  (std::abs(double(host.xyz[i])) + 1e-6 * peak));
      total += host.xyz[i];
    }
    std::printf("  largest relative difference %.2g\n", worst);
    EXPECT_GT(total, 0);
    EXPECT_LT(worst, 1e-4);
  }
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
