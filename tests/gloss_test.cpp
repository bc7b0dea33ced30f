// A tabulated gloss lobe (not only the ideal mirror the furnace checks): the three integrators
// sample and evaluate it independently — backward by lobe sampling and next-event estimation,
// forward by scattering photons and splatting the lobe towards the camera, photon mapping by
// camera paths through it — and must agree on a Cornell box with a glossy floor.
#include <gtest/gtest.h>

#include <cmath>

#include "render/device_scene.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Gloss, LobeTableIsANormalizedDensityWithItsCdf) {
  GlossDesc g;
  g.reflectance = 0.3;
  g.cone_deg = 12;
  g.profile_deg = {0, 4, 8, 12};
  g.profile_value = {1, 0.7, 0.25, 0};
  std::vector<float> t = gloss_lobe_table(g);
  ASSERT_EQ(t.size(), 2u * KASHA_LOBE_CELLS);
  double total = 0, cone = 12 * M_PI / 180;
  for (int k = 0; k < KASHA_LOBE_CELLS; ++k) {
    double lo = cone * k / KASHA_LOBE_CELLS, hi = cone * (k + 1) / KASHA_LOBE_CELLS;
    total += t[k] * 2 * M_PI * (std::cos(lo) - std::cos(hi));  // ∫ p dω over the ring
    EXPECT_NEAR(t[KASHA_LOBE_CELLS + k], total, 1e-5);
    if (k > 0) {
      EXPECT_LE(t[k], t[k - 1] + 1e-6);  // the profile falls away from the mirror direction
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-5);
}

TEST(Gloss, IntegratorsAgreeOnAGlossyFloor) {
  for (const char* integrator : {"forward", "photon"}) {
    ComparedRenders pair =
        render_against_backward("glossy_cornell_box.json", integrator, 24,
                                std::string(integrator) == "forward" ? 1 << 19 : 1 << 17);
    std::map<std::string, std::vector<size_t>> regions =
        primary_hit_regions(pair.tested.scene, pair.camera);
    ASSERT_TRUE(regions.count("glossy_white"));
    for (const auto& [name, pixels] : regions) {
      BinStats t = pixel_statistics(pair.tested.image, false, pixels);
      BinStats b = pixel_statistics(pair.backward.image, false, pixels);
      for (int c = 0; c < 3; ++c)
        EXPECT_LT(std::abs(t.mean[c] - b.mean[c]), 0.03 * b.mean[c])
            << integrator << " " << name << " row " << c << ": " << t.mean[c] << " vs backward "
            << b.mean[c];
    }
  }
}
