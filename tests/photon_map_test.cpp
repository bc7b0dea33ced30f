// Photon mapping's device gather against nanoflann's, the compactness of what it stores, and radii
// that catch nothing (its furnace and agreement tests are in integrator_*_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "kernel_harness.h"
#include "render/device_scene.h"
#include "render/record_bytes.h"
#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Photon, SppmStatisticsFollowAHandWorkedExample) {
  // One pixel's statistics on the device (kernels/photon/sppm_statistics.h) against the formulas
  // worked by hand. Pass 1 finds 4 photons in radius 2, pass 2 none, pass 3 eight with its flux
  // scaled by 2 (a pass cut short at half its photons): n = 4α, R² = 4·4α/4, τ = φ1·R²/4; then n' =
  // 4α + 8α, R'² = R²·n'/(n + 8), τ' = (τ + 2φ3)·R'²/R²; radiance τ'/(3π R'² Δλ).
  const char* source = R"(
#include "sampling/sampling.h"
#include "photon/sppm_statistics.h"
__kernel void sppm(__global const float* passes, int count, float alpha, float r0, float bin_nm,
                   __global float* out) {
  if (get_global_id(0) != 0) return;
  out[0] = r0, out[1] = 0.0f, out[2] = out[3] = out[4] = 0.0f;
  for (int k = 0; k < count; ++k)
    sppm_add_pass(out, out + 1, out + 2, 3, passes + 5 * k + 2, passes[5 * k + 1], (int)passes[5 * k],
                  alpha);
  for (int r = 0; r < 3; ++r) out[5 + r] = sppm_radiance(out[0], out + 2, r, (float)count, bin_nm);
}
)";
  const double alpha = 0.5, bin_nm = 10;
  TestKernel k(source, "sppm_test.cl", "sppm");
  // Per pass: found, scale, flux per row.
  k.input(0, std::vector<float>{4, 1, 10, 20, 0, 0, 1, 0, 0, 0, 8, 2, 3, 6, 0});
  k.scalar(1, cl_int(3));
  k.scalar(2, cl_float(alpha));
  k.scalar(3, cl_float(2));
  k.scalar(4, cl_float(bin_nm));
  k.output(5, 8);
  k.run(1);
  std::vector<float> out = k.read(5);
  double n = 4 * alpha, r2 = 4.0 * n / 4, tau = 10.0 * r2 / 4;
  double n2 = n + 8 * alpha, r2b = r2 * n2 / (n + 8);
  tau = (tau + 2 * 3.0) * r2b / r2;
  EXPECT_NEAR(out[0], std::sqrt(r2b), 1e-6);
  EXPECT_NEAR(out[1], n2, 1e-6);
  EXPECT_NEAR(out[2], tau, 1e-5 * tau);
  EXPECT_NEAR(out[3], 2 * tau, 2e-5 * tau);
  EXPECT_EQ(out[4], 0.0f);
  const double radiance = tau / (3 * M_PI * r2b * bin_nm);
  EXPECT_NEAR(out[5], radiance, 1e-5 * radiance);
  EXPECT_NEAR(out[6], 2 * radiance, 2e-5 * radiance);
}

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
    s.integrator_settings.gather = Gather::device;
    Image device = render_scene(source_path(c.scene), s).image;
    s.integrator_settings.gather = Gather::host;
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
  EXPECT_EQ(photon_record_bytes(fluorescent), (8 + M) * sizeof(float));
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
