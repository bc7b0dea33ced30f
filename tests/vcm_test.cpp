// Vertex connection and merging's MIS weights (kernels/vcm.cl): for each path length, the
// weighted techniques together must estimate what one unweighted technique estimates alone — the
// weights of every path sum to one. The reference is path tracing without next-event estimation
// (the vcm kernel's emission-only hook), in a box lit by a large lamp so that it converges; a
// weight with one technique's density left out must fail the same comparison. The furnaces and
// the agreement with backward are in the registry-wide tests (integrator_furnace_test.cpp,
// integrator_agreement_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// A grey box with a large lamp under its ceiling (facing down) and a yellow Lambert block: paths
// of every length, fluorescence left out so that bins stay apart.
std::string lamp_box() {
  return write_file("vcm_lamp_box.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, -0.2, 0.9], "look_at": [0, 0.1, -1], "fov_deg": 70,
               "width": 64, "height": 64},
    "materials": {"grey": {"passive": {"reflectance": 0.5}},
                  "yellow": {"passive": {"reflectance": {"nm": [380, 500, 560, 780],
                                                          "value": [0.05, 0.1, 0.7, 0.8]}}},
                  "lamp": {"passive": {"reflectance": 0.2}}},
    "shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "grey",
                "inward": true},
               {"type": "box", "min": [-0.5, -1, -0.6], "max": [0.1, -0.4, 0.0],
                "material": "yellow"},
               {"type": "quad", "corner": [-0.6, 0.98, -0.6], "u": [1.2, 0, 0], "v": [0, 0, 1.2],
                "material": "lamp", "emission": {"blackbody_K": 5000, "scale": 1e-5}}]})");
}

RenderResult render_length(const std::string& integrator, int length, int passes,
                           bool emission_only, bool drop_density = false, int spp = 0,
                           const std::string& merges = "first") {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = passes;
  s.integrator_settings.spp = spp;
  s.integrator_settings.merges = merges;
  s.spectral = false;
  s.integrator_settings.vcm_length = length;
  s.integrator_settings.vcm_emission_only = emission_only;
  s.integrator_settings.vcm_drop_density = drop_density;
  return render_scene(lamp_box(), s);
}

// Per XYZ row: (mean of a − mean of b) over its standard error, the images independent.
std::array<double, 3> z_scores(const Image& a, const Image& b, std::array<double, 3>* relative) {
  BinStats sa = pixel_statistics(a, false), sb = pixel_statistics(b, false);
  std::array<double, 3> z{};
  for (int k = 0; k < 3; ++k) {
    const double se = std::hypot(sa.standard_error[k], sb.standard_error[k]);
    z[k] = (sa.mean[k] - sb.mean[k]) / se;
    (*relative)[k] = sa.mean[k] / sb.mean[k] - 1;
  }
  return z;
}

// The plain estimate of each path length, computed once for the tests below.
const Image& plain(int length) {
  static std::map<int, Image> images;
  auto it = images.find(length);
  if (it == images.end())
    it = images.emplace(length, render_length("bpt", length, 128, true).image).first;
  return it->second;
}

}  // namespace

// `integrator` restricted to paths of `length` segments against the plain estimate: z-scores per
// XYZ row, and the relative differences in *relative.
std::array<double, 3> against_plain(const std::string& integrator, int length,
                                    std::array<double, 3>* relative, int spp = 0,
                                    const std::string& merges = "first") {
  RenderResult weighted = render_length(integrator, length, 16, false, false, spp, merges);
  std::array<double, 3> z = z_scores(weighted.image, plain(length), relative);
  std::printf(
      "  length %d, %d camera paths a pixel, merges %s: %s / plain - 1 = %+.2f %% (Y, "
      "%+.1f standard errors)\n",
      length, spp, merges.c_str(), integrator.c_str(), 100 * (*relative)[1], z[1]);
  return z;
}

// Lengths 2 (direct light: emission hit, next-event estimation, light tracing), 3 and 4 (all of
// bpt's techniques, connections of both subpaths' inner vertices among them).
// Then with three camera paths a pixel (light tracing weighed against three).
TEST(Vcm, BptWeightsSumToOnePerPathLength) {
  for (int length : {2, 3, 4}) {
    std::array<double, 3> relative;
    std::array<double, 3> z = against_plain("bpt", length, &relative);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(std::abs(z[k]), 4.0) << "length " << length << " row " << k;
  }
  for (int length : {2, 3}) {
    std::array<double, 3> relative;
    std::array<double, 3> z = against_plain("bpt", length, &relative, 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(std::abs(z[k]), 4.0) << "length " << length << " row " << k;
  }
}

// Merges join the weights: a vertex's merge is weighed against the connections that make the
// same path, so the sum holds within merging's bias at this radius (1 % here) — merging at the
// camera path's first vertex (the default), at every vertex, and with three camera paths a pixel.
TEST(Vcm, VcmWeightsSumToOnePerPathLength) {
  for (const auto& [merges, spp] :
       std::vector<std::pair<std::string, int>>{{"first", 0}, {"every", 0}, {"first", 3}})
    for (int length : {2, 3}) {
      std::array<double, 3> relative;
      std::array<double, 3> z = against_plain("vcm", length, &relative, spp, merges);
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(std::abs(z[k]) < 4.0 || std::abs(relative[k]) < 0.01)
            << "length " << length << " merges " << merges << " spp " << spp << " row " << k;
    }
}

// Light tracing's weight without next-event estimation's density: direct light counted more
// than once where both reach a point. The comparison above must catch it.
TEST(Vcm, AWeightWithADensityDroppedFails) {
  RenderResult wrong = render_length("bpt", 2, 16, false, true);
  std::array<double, 3> relative;
  std::array<double, 3> z = z_scores(wrong.image, plain(2), &relative);
  std::printf(
      "  length 2, density dropped: bpt / plain - 1 = %+.2f %% (Y, %+.1f standard errors)\n",
      100 * relative[1], z[1]);
  EXPECT_GT(z[1], 6.0);
}
