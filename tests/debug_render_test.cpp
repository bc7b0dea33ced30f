// The first-hit kernel against geometry worked out by hand: an emitter covering a known part of
// the image, seen from the front and from behind, through the camera conventions of
// docs/formats.md#scenes
#include <gtest/gtest.h>

#include <cmath>

#include "color/cie_observer.h"
#include "film/film.h"
#include "render/device_scene.h"
#include "render/render_job.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;

namespace {

struct Rendered {
  Scene scene;
  Image image;
  long long spp;
};

// A 128x64 camera at the origin looking along +z (fov 90° over the height) at a quad emitter in the
// plane z = 1 covering x < 0.3: on the image plane x spans [-2, 2], so (0.3 + 2)/4 = 57.5 % of the
// image width is covered, on the image's right because right = forward × up = -x.
Rendered render(bool facing_camera, bool spectral, int passes) {
  // u × v points back at the camera (−z) when it faces it.
  std::string corner = facing_camera ? "[-9, 9, 1]" : "[-9, -9, 1]";
  std::string v = facing_camera ? "[0, -18, 0]" : "[0, 18, 0]";
  std::string path = test::write_file("emitter.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov_deg": 90, "width": 128, "height": 64},
    "materials": {"black": {}},
    "shapes": [{"type": "quad", "corner": )" + corner + R"(, "u": [9.3, 0, 0], "v": )" +
                                                          v + R"(, "material": "black",
                "emission": {"gaussian_nm": 550, "fwhm_nm": 60, "scale": 3}}]})");
  Rendered r{load_scene(path), {}, 0};
  ClContext cl(0);
  DeviceScene ds(cl, r.scene);
  IntegratorSettings settings;
  settings.view = DebugView::emission;
  settings.spp = 16;
  settings.seed = 7;
  RenderJob job(cl, r.scene, ds, "debug", settings, spectral);
  for (int p = 0; p < passes; ++p) job.pass(p);
  r.image = job.film().image();
  r.spp = job.film().samples_per_pixel();
  return r;
}

}  // namespace

TEST(DebugRender, EmissionCoversTheRightFractionWithTheRightRadiance) {
  Rendered r = render(true, true, 4);
  const std::vector<double>& le = r.scene.emitters[0].per_bin;
  BinnedObserver obs(r.scene.grid);
  double y_emitter = obs.xyz(le, r.scene.grid.bin_nm)[1];

  // Fully covered pixels hold the emitter's radiance exactly, bin by bin; uncovered ones zero.
  int n = r.scene.grid.bins;
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR(r.image.spectral[(10 * 128 + 120) * n + i], le[i], 1e-5 * (1 + le[i]));
  for (int i = 0; i < n; ++i) EXPECT_EQ(r.image.spectral[(10 * 128 + 5) * n + i], 0.0f);

  // The image mean is 57.5 % of the emitter's Y; only the column holding the edge is noisy.
  double mean = 0;
  for (size_t p = 0; p < r.image.pixels(); ++p) mean += r.image.xyz[3 * p + 1];
  mean /= r.image.pixels();
  double edge_fraction = 0.575 * 128 - std::floor(0.575 * 128);
  double sigma =
      y_emitter * std::sqrt(64 * edge_fraction * (1 - edge_fraction) / r.spp) / r.image.pixels();
  EXPECT_NEAR(mean, 0.575 * y_emitter, 4 * sigma + 1e-6 * y_emitter);
  // The covered side is the image's right (+x is on the left).
  EXPECT_GT(r.image.xyz[3 * (32 * 128 + 127) + 1], 0);
  EXPECT_EQ(r.image.xyz[3 * (32 * 128 + 0) + 1], 0);
}

TEST(DebugRender, EmittersAreDarkFromBehindAndXyzFilmMatchesSpectral) {
  Rendered back = render(false, false, 1);
  for (float v : back.image.xyz) EXPECT_EQ(v, 0.0f);
  Rendered xyz = render(true, false, 1), spectral = render(true, true, 1);
  // The same samples through an XYZ film and a spectral film agree (same seed).
  for (size_t i = 0; i < xyz.image.xyz.size(); ++i)
    EXPECT_NEAR(xyz.image.xyz[i], spectral.image.xyz[i], 1e-4 * (1 + spectral.image.xyz[i]));
}
