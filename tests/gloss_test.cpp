// The tabulated gloss lobe's table (the integrators' agreement on a glossy floor is in
// integrator_agreement_test.cpp).
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
