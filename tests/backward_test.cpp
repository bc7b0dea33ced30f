// The backward integrator against a brute-force full-matrix path state, and for finiteness and
// convergence (its furnace tests are in integrator_furnace_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

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
    s.integrator_settings.spp = 64;
    RenderResult rank1 = render_scene(path, s);
    s.hooks.full_matrix = true;
    s.integrator_settings.seed = 2;
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
    s.integrator_settings.spp = 8;
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
  s.integrator_settings.spp = 2;
  s.integrator_settings.sampler =
      Sampler::independent;  // Monte Carlo's rate; Sobol points may do better
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
