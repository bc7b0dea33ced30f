// The pixel filter (docs/formats.md#pixel-filters) against its analytic image: an emitter whose
// edge runs down the middle of the image, at film column 8 of 16. A pixel's value is the share of
// the filter, centred on the pixel, that falls beyond the edge: for pbrt-v4's triangle of radius 1
// 0, 1/8, 7/8 and 1 for columns 6 to 9; for its gaussian the integral of pbrt-v4's formula
// (PixelFilter::evaluate_1d, not the kernels' table). Camera paths (backward) test the sampled
// offsets; light tracing (forward) tests the splats, which choose a pixel by the filter's weight;
// vcm, the default, weighs the two.
#include <gtest/gtest.h>

#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// The share of the filter at a pixel centre `d` pixels from the edge (positive: on the lit side)
// that lies on the lit side, by the midpoint rule on pbrt-v4's formula.
double lit_share(const PixelFilter& f, double d) {
  const int n = 20000;
  const double r = f.radius[0];
  double lit = 0, all = 0;
  for (int k = 0; k < n; ++k) {
    const double x = -r + 2 * r * (k + 0.5) / n, w = f.evaluate_1d(0, x);
    all += w;
    if (d + x >= 0) lit += w;
  }
  return lit / all;
}

struct FilterCase {
  std::string filter, integrator;
};

void PrintTo(const FilterCase& c, std::ostream* os) {
  *os << c.filter << " through " << c.integrator;
}

class PixelFilterEdge : public ::testing::TestWithParam<FilterCase> {};

TEST_P(PixelFilterEdge, ColumnsAcrossAnEdgeAreTheFiltersShare) {
  const FilterCase& c = GetParam();
  const std::string path = write_file("edge.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_deg": 40, "width": 16, "height": 4},
    "materials": {"black": {"passive": {"reflectance": 0}}},
    "shapes": [{"type": "quad", "corner": [0, -1, -1], "u": [2, 0, 0], "v": [0, 2, 0],
                "material": "black", "emission": {"blackbody_K": 5000, "scale": 1e-6}}]})");
  RenderSettings s;
  s.integrator = c.integrator;
  Camera cam;
  cam.position = {0, 0, 0};
  cam.look_at = {0, 0, -1};
  cam.fov_deg = 40;
  cam.width = 16;
  cam.height = 4;
  cam.filter = default_pixel_filter(c.filter);
  if (c.filter == "triangle") cam.filter.radius = {1, 1};
  s.camera = cam;
  s.passes = c.integrator == "backward" ? 16 : 8;
  s.spectral = false;
  s.integrator_settings.spp = 64;
  s.integrator_settings.photons = 1 << 16;
  const RenderResult r = render_scene(path, s);
  auto column = [&](int x) {
    double sum = 0;
    for (int y = 0; y < cam.height; ++y) sum += r.image.xyz[3 * (y * cam.width + x) + 1];
    return sum / cam.height;
  };
  double lit = 0;  // columns 12-15: 3.5 pixels and more from the edge, wholly lit
  for (int x = 12; x < 16; ++x) lit += column(x) / 4;
  ASSERT_GT(lit, 0);
  for (int x = 5; x <= 10; ++x) {
    const double expected = lit_share(cam.filter, x + 0.5 - 8);
    EXPECT_NEAR(column(x) / lit, expected, 0.02) << "column " << x;
  }
}

INSTANTIATE_TEST_SUITE_P(Filters, PixelFilterEdge,
                         ::testing::Values(FilterCase{"triangle", "backward"},
                                           FilterCase{"triangle", "forward"},
                                           FilterCase{"gaussian", "backward"},
                                           FilterCase{"gaussian", "forward"},
                                           FilterCase{"gaussian", "vcm"}));

}  // namespace
