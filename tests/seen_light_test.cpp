// The host probe that picks the pixels where vcm takes the light seen through delta bounces from
// extra samples (integrators/vcm/seen_light.h): a lamp's outline, seen directly or in a mirror, is
// picked; its inside, where every sample sees the same light, and the pixels far from it are not.
// That the extra samples estimate what the camera paths alone do is vcm_test.cpp's (its plain
// estimate takes none).
#include "integrators/vcm/seen_light.h"

#include <gtest/gtest.h>

#include "test_support.h"

using namespace kasha;

namespace {

// A 32² view of a grey wall with a square lamp before it, facing the camera; with `mirror`, the
// camera looks at a mirror instead and sees a lamp behind it in the mirror, as large in the view.
std::vector<int> picked(bool mirror) {
  const std::string lamp =
      mirror ? R"({"type": "quad", "corner": [-1.5, -1.5, 1.9], "u": [0, 3, 0], "v": [3, 0, 0],
                   "material": "grey", "emission": {"blackbody_K": 5000, "scale": 1e-5}},
                  {"type": "quad", "corner": [-3, -3, -1.9], "u": [6, 0, 0], "v": [0, 6, 0],
                   "material": "mirror"})"
             : R"({"type": "quad", "corner": [-0.5, -0.5, -1.9], "u": [1, 0, 0], "v": [0, 1, 0],
                   "material": "grey", "emission": {"blackbody_K": 5000, "scale": 1e-5}},
                  {"type": "quad", "corner": [-3, -3, -2], "u": [6, 0, 0], "v": [0, 6, 0],
                   "material": "grey"})";
  const Scene scene = load_scene(test::write_file(mirror ? "seen_mirror.json" : "seen_lamp.json",
                                                  R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_deg": 60,
               "width": 32, "height": 32},
    "materials": {"grey": {"passive": {"reflectance": 0.5}},
                  "mirror": {"gloss": {"reflectance": 0.9, "mirror": true}}},
    "shapes": [)" + lamp + "]}"));
  const EmbreeScene embree(scene.triangles);
  return seen_light_pixels(scene, embree, scene.camera.to_kernel());
}

void expect_outline(const std::vector<int>& p) {
  ASSERT_EQ(p.size(), 32u * 32u);
  auto at = [&](int x, int y) { return p[static_cast<size_t>(y) * 32 + x]; };
  EXPECT_EQ(at(16, 16), 0) << "inside the lamp";
  EXPECT_EQ(at(1, 1), 0) << "far from it";
  // The lamp spans pixels 9 to 22 or so: its left and right edges on the middle row.
  int left = 0, right = 0, all = 0;
  for (int x = 5; x <= 12; ++x) left += at(x, 16);
  for (int x = 19; x <= 26; ++x) right += at(x, 16);
  for (int v : p) all += v;
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
  EXPECT_GT(all, 40);
  EXPECT_LT(all, 400);
}

}  // namespace

TEST(SeenLight, PicksALampsOutline) {
  expect_outline(picked(false));
}

TEST(SeenLight, PicksALampsOutlineInAMirror) {
  expect_outline(picked(true));
}
