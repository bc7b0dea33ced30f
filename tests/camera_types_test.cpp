// pbrt-v4's cameras (docs/formats.md#camera) in a furnace: inside a uniformly emitting sphere
// every pixel of every camera sees the analytic furnace radiance. Camera paths (backward) test
// the rays; light tracing (forward) tests the importance camera_pixel gives a splat; vcm weighs
// both with the camera's density. Bands of rows and columns are checked apart, so a mapping
// whose Jacobian is wrong somewhere (an equirectangular pole, a lens edge) shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

struct CameraCase {
  std::string name, integrator;
};

void PrintTo(const CameraCase& c, std::ostream* os) {
  *os << c.name << " through " << c.integrator;
}

Camera camera_of(const std::string& name) {
  Camera c;
  c.position = {0.2, -0.1, 0.3};
  c.look_at = {1, 0.3, -0.5};
  c.width = 24;
  c.height = 16;
  if (name == "thin_lens") {
    c.lens_radius = 0.15;
    c.focal_distance = 0.8;
    c.screen_window = std::array<double, 4>{-0.5, 1.5, -1, 0.6};  // off centre
  } else if (name == "orthographic") {
    c.type = "orthographic";
    c.screen_window = std::array<double, 4>{-0.6, 1.0, -0.7, 0.5};
  } else if (name != "pinhole") {
    c.type = "spherical";
    c.mapping = name;
  }
  return c;
}

// The mean over the lit bins of a set of pixels, relative to the truth.
double relative_mean(const Image& img, const std::vector<double>& truth,
                     const std::vector<size_t>& pixels) {
  double peak = *std::max_element(truth.begin(), truth.end()), sum = 0;
  size_t n = 0, N = truth.size();
  for (size_t p : pixels)
    for (size_t i = 0; i < N; ++i)
      if (truth[i] >= 1e-2 * peak) {
        sum += img.spectral[p * N + i] / truth[i];
        ++n;
      }
  return sum / n;
}

class CameraFurnace : public ::testing::TestWithParam<CameraCase> {};

TEST_P(CameraFurnace, EveryBandSeesTheFurnaceRadiance) {
  const CameraCase& c = GetParam();
  const std::string path = source_path("scenes/furnace_passive.json");
  RenderSettings s;
  s.integrator = c.integrator;
  s.camera = camera_of(c.name);
  s.passes = c.integrator == "backward" ? 4 : 8;
  s.integrator_settings.spp = 16;
  s.integrator_settings.photons = 1 << 15;
  Scene scene = load_scene(path, s.grid);
  Furnace f = analyze_furnace(scene);
  ASSERT_TRUE(f.qualifies) << f.why_not;
  RenderResult r = render_scene(path, s);
  const int w = s.camera->width, h = s.camera->height;
  // Four bands of rows, four of columns, and the whole image.
  std::vector<std::vector<size_t>> groups(9);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = static_cast<size_t>(y) * w + x;
      groups[y * 4 / h].push_back(p);
      groups[4 + x * 4 / w].push_back(p);
      groups[8].push_back(p);
    }
  std::printf("  %s, %s:", c.name.c_str(), c.integrator.c_str());
  for (const auto& g : groups) std::printf(" %.4f", relative_mean(r.image, f.radiance, g));
  std::printf("\n");
  for (size_t k = 0; k < groups.size(); ++k)
    EXPECT_NEAR(relative_mean(r.image, f.radiance, groups[k]), 1.0, k == 8 ? 0.015 : 0.04)
        << "group " << k;
}

std::vector<CameraCase> all_cases() {
  std::vector<CameraCase> cases;
  for (const char* name : {"pinhole", "thin_lens", "orthographic", "equalarea", "equirectangular"})
    for (const char* integrator : {"backward", "forward", "vcm"})
      cases.push_back({name, integrator});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Types, CameraFurnace, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           return info.param.name + "_" + info.param.integrator;
                         });

}  // namespace
