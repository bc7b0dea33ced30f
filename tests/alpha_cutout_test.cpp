// Alpha cut-outs (docs/formats.md#alpha): a shape's "alpha" as a constant or a texture, against
// ground truth: alpha 0 is never hit, alpha 1 always, a constant a stops the share a of the rays
// (pbrt-v4's stochastic test, fixed by the ray's hash), a 0/1 checkerboard exactly its solid
// squares; the OpenCL traversal and Embree's reference (its filter functions) agree ray by ray,
// closest hits and shadow queries alike; and a render sees the sky through the holes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "analytic_floor.h"
#include "geometry/cl_traversal.h"
#include "geometry/embree_scene.h"
#include "render/device_scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

ClContext& device() {
  static ClContext context(0);
  return context;
}

const char* const kSky = R"({"type": "infinite", "radiance": 0.7})";
const char* const kGrey = R"({"passive": {"reflectance": 0.8}})";
// Solid (alpha 1) on even squares, open (alpha 0) on odd ones: 4 × 4 squares over the floor.
const char* const kChecker = R"("textures": {"holes": {"type": "checkerboard", "even": 1,
    "odd": 0, "uscale": 4, "vscale": 4}})";

// Rays straight down at uniform points over the floor (−2 ≤ x, y ≤ 2) from z = 2.
std::vector<KRay> down_rays(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-2.0f, 2.0f);
  std::vector<KRay> rays(n);
  for (KRay& r : rays) r = KRay{{xy(rng), xy(rng), 2.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 10.0f};
  return rays;
}

// The fraction of the rays each traversal stops, after checking both agree ray by ray.
double stopped_share(const std::string& path, const std::vector<KRay>& rays) {
  Scene scene = load_scene(path);
  KernelSceneData data(scene);
  AlphaCutouts alpha = alpha_cutouts(data);
  EmbreeScene embree(scene.triangles, alpha);
  ClTraversal traversal(device(), data.bvh, alpha);
  std::vector<KHit> expected, got = traversal.closest(rays);
  std::vector<int> occluded = traversal.occluded(rays);
  embree.intersect_all(rays, expected);
  size_t stopped = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(got[i].prim, expected[i].prim) << "ray " << i;
    EXPECT_EQ(occluded[i], embree.occluded(rays[i]) ? 1 : 0) << "ray " << i;
    EXPECT_EQ(occluded[i], got[i].prim >= 0 ? 1 : 0) << "ray " << i;
    stopped += got[i].prim >= 0;
  }
  return static_cast<double>(stopped) / rays.size();
}

}  // namespace

TEST(AlphaCutout, ZeroIsNeverHitAndOneAlways) {
  const std::vector<KRay> rays = down_rays(4000, 1);
  EXPECT_EQ(stopped_share(floor_scene("alpha0", kGrey, kSky, "", R"("alpha": 0)"), rays), 0.0);
  EXPECT_EQ(stopped_share(floor_scene("alpha1", kGrey, kSky, "", R"("alpha": 1)"), rays), 1.0);
}

TEST(AlphaCutout, AConstantStopsItsShareOfRays) {
  const size_t n = 40000;
  const double share =
      stopped_share(floor_scene("alpha03", kGrey, kSky, "", R"("alpha": 0.3)"), down_rays(n, 2));
  EXPECT_NEAR(share, 0.3, 4 * std::sqrt(0.3 * 0.7 / n));
}

TEST(AlphaCutout, ACheckerboardStopsExactlyItsSolidSquaresBehindALeaf) {
  // A leaf of alpha 0.5 at z = 1 over the checkered floor: a ray passes the leaf with probability
  // 0.5, then the floor stops it on a solid square only.
  const std::string leaf =
      R"({"type": "quad", "corner": [-2, -2, 1], "u": [4, 0, 0], "v": [0, 4, 0],
          "material": "floor", "alpha": 0.5})";
  const std::string path =
      floor_scene("alpha_checker", kGrey, kSky, kChecker, R"("alpha": "holes")", leaf);
  const std::vector<KRay> rays = down_rays(40000, 3);
  Scene scene = load_scene(path);
  KernelSceneData data(scene);
  AlphaCutouts alpha = alpha_cutouts(data);
  EmbreeScene embree(scene.triangles, alpha);
  ClTraversal traversal(device(), data.bvh, alpha);
  std::vector<KHit> got = traversal.closest(rays);
  size_t on_leaf = 0, through = 0, wrong = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const KHit expected = embree.intersect(rays[i]);
    EXPECT_EQ(got[i].prim, expected.prim) << "ray " << i;
    const int floor_prim = got[i].prim >= 0 && got[i].prim < 2;
    if (got[i].prim >= 2) {
      ++on_leaf;
      continue;
    }
    ++through;
    const float u = (rays[i].org[0] + 2) / 4 * 4, v = (rays[i].org[1] + 2) / 4 * 4;
    const bool solid = (static_cast<int>(std::floor(u)) + static_cast<int>(std::floor(v))) % 2 == 0;
    if (floor_prim != solid) ++wrong;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_NEAR(static_cast<double>(on_leaf) / rays.size(), 0.5, 4 * std::sqrt(0.25 / rays.size()));
  EXPECT_GT(through, rays.size() / 3);
}

TEST(AlphaCutout, ATextureOfTexturesCutsWhereItsPatternSays) {
  // A 3D checkerboard of alpha 1 and 0 in a texture space scaled by 0.5 and lifted by 0.3 (the
  // floor z = 0 is mid-cube there): a program evaluated at the point, in both traversals alike.
  const char* const cubes = R"("textures": {"cubes": {"type": "checkerboard", "dimension": 3,
      "even": 1, "odd": 0, "transform": {"scale": 0.5, "translate": [0, 0, 0.3]}}})";
  const std::string path = floor_scene("alpha_program", kGrey, kSky, cubes, R"("alpha": "cubes")");
  const std::vector<KRay> rays = down_rays(20000, 4);
  Scene scene = load_scene(path);
  KernelSceneData data(scene);
  AlphaCutouts alpha = alpha_cutouts(data);
  ASSERT_FALSE(alpha.ops.empty());
  EmbreeScene embree(scene.triangles, alpha);
  ClTraversal traversal(device(), data.bvh, alpha);
  std::vector<KHit> got = traversal.closest(rays);
  size_t wrong = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(got[i].prim, embree.intersect(rays[i]).prim) << "ray " << i;
    const int cell = static_cast<int>(std::floor(rays[i].org[0] / 0.5)) +
                     static_cast<int>(std::floor(rays[i].org[1] / 0.5)) +
                     static_cast<int>(std::floor(-0.3 / 0.5));
    if ((got[i].prim >= 0) != (cell % 2 == 0)) ++wrong;
  }
  EXPECT_EQ(wrong, 0u);
}

TEST(AlphaCutout, TheSkyIsSeenThroughTheHoles) {
  const std::string scene =
      floor_scene("alpha_render", kGrey, kSky, kChecker, R"("alpha": "holes")");
  auto radiance = [](const Scene&, const Eigen::Vector3d& x, int) {
    const double u = (x.x() + 2) / 4 * 4, v = (x.y() + 2) / 4 * 4;
    const bool solid = (static_cast<int>(std::floor(u)) + static_cast<int>(std::floor(v))) % 2 == 0;
    return solid ? 0.8 * 0.7 : 0.7;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "photon", radiance, 16, 1 << 14, 1);
}
