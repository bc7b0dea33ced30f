// Object instancing (docs/formats.md#instances): an object placed more than once is stored once
// and rendered as if every placement were written out. Every integrator renders the instanced
// scene (tests/instanced_scene.cpp: 9 placements, rotated, scaled unevenly, one mirrored) as it
// renders the same scene flattened; the loader keeps one copy; pbrt-v4's ObjectInstance becomes
// kasha's instances. Traversal against Embree: traversal_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "instanced_scene.h"
#include "render/device_scene.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

TEST(Instancing, EachObjectIsStoredOnce) {
  const Scene scene = load_scene(instanced_scene(false));
  const Scene flat = load_scene(instanced_scene(true));
  ASSERT_EQ(scene.instances.objects.size(), 1u);  // "single", placed once, joins the scene's own
  EXPECT_EQ(scene.instances.placements.size(), 9u);
  EXPECT_EQ(scene.object_names, std::vector<std::string>{"thing"});
  const int object = scene.instances.objects[0].triangle_count;
  EXPECT_EQ(scene.triangles.size(), size_t(scene.instances.world_triangles + object));
  EXPECT_EQ(scene.placed_triangles(), flat.triangles.size());
  EXPECT_EQ(KernelSceneData(scene).bvh.triangles.size(), scene.triangles.size());
  // The lights' photons leave a sphere around the placed geometry: the placed object boxes'
  // (conservative: a rotated box is larger than what it holds).
  Eigen::Vector3d c1, c2;
  double r1, r2;
  scene.bounding_sphere(c1, r1);
  flat.bounding_sphere(c2, r2);
  EXPECT_GE(r1, r2 * (1 - 1e-6));
  EXPECT_LT(r1, 1.05 * r2);
  EXPECT_LT((c1 - c2).norm(), 0.05 * r2);
}

TEST(Instancing, BadInstancesAreOneLine) {
  const auto refused = [](const std::string& tail) {
    return error_of([&] {
      load_scene(write_file("instanced_bad.json", R"({"kasha_scene": 1,
        "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
        "materials": {"m": {"passive": {"reflectance": 0.5}}},
        "shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "m"}])" +
                                                      tail + "}"));
    });
  };
  const std::string quad =
      R"({"type": "quad", "corner": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0], "material": "m")";
  EXPECT_NE(refused(R"(, "instances": [{"object": "a"}])").find("place the scene's \"objects\""),
            std::string::npos);
  EXPECT_NE(refused(R"(, "objects": {"a": [)" + quad + R"(}]}, "instances": [{"object": "b"}])")
                .find("/instances/0/object: no object named \"b\""),
            std::string::npos);
  EXPECT_NE(refused(R"(, "objects": {"a": [)" + quad +
                    R"(, "emission": 1}]}, "instances": [{"object": "a"}, {"object": "a"}])")
                .find("a shape of an object does not emit"),
            std::string::npos);
  EXPECT_NE(refused(R"(, "objects": {"a": [)" + quad +
                    R"(}]}, "instances": [{"object": "a"}, {"object": "a",
                    "transform": {"scale": 1e17, "translate": [1e18, 0, 0]}}])")
                .find("/instances/1: the object placed here has a vertex"),
            std::string::npos);
}

class InstancedRender : public ::testing::TestWithParam<std::string> {};

// The same sample sequence through both scenes: the images differ only where float rounding of
// the placed triangles sends a path another way, so their mean difference is within its noise.
TEST_P(InstancedRender, MatchesTheFlattenedScene) {
  const std::string integrator = GetParam();
  RenderSettings s;
  s.integrator = integrator;
  s.spectral = false;
  s.passes = 4;
  s.integrator_settings.spp = 4;
  s.integrator_settings.photons = 1 << 13;
  const RenderResult instanced = render_scene(instanced_scene(false), s);
  const RenderResult flat = render_scene(instanced_scene(true), s);
  const BinStats mean = pixel_statistics(flat.image, false);
  const BinStats diff = difference_statistics(instanced.image, flat.image, false);
  for (int row = 0; row < 3; ++row) {
    ASSERT_GT(mean.mean[row], 0);
    EXPECT_LE(std::abs(diff.mean[row]), 4 * diff.standard_error[row] + 2e-3 * mean.mean[row])
        << integrator << " row " << row << ": mean " << mean.mean[row];
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, InstancedRender,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const auto& info) { return info.param; });

}  // namespace
