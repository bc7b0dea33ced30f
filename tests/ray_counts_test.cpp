// The rays kernels count (kernels/geometry/hit_point.h, add_ray_counts; `kasha bench`'s rays/s): exact
// where the number of rays is known, and 64-bit sums that survive the low word wrapping.
#include <gtest/gtest.h>

#include "film/pass_result.h"
#include "kernel_harness.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;

namespace {

test::RenderResult render(const std::string& scene, const std::string& integrator, int depth_guard,
                          int spp = 4) {
  test::RenderSettings s;
  s.integrator = integrator;
  s.passes = 2;
  s.spectral = false;
  s.integrator_settings.depth_guard = depth_guard;
  if (integrator != "forward") s.integrator_settings.spp = spp;
  s.integrator_settings.photons = 1 << 14;
  return render_scene(test::source_path(scene), s);
}

}  // namespace

// The first-hit views trace one closest-hit ray per camera sample, hit or miss, and no other.
TEST(RayCounts, DebugCountsOneClosestRayPerCameraSample) {
  test::RenderResult r = render("scenes/cornell_box.json", "debug", 1 << 18);
  const double paths = r.scene.camera.width * r.scene.camera.height * 4.0 * 2;
  EXPECT_EQ(r.counters.closest_rays, paths);
  EXPECT_EQ(r.counters.shadow_rays, 0);
}

// Inside a closed furnace every ray hits and no path ends by itself before the depth guard (no
// black surface, roulette from the third vertex on), so backward traces exactly --depth-guard
// closest-hit rays per path: 1 (the camera ray) and 3. Next-event estimation sends at most one
// shadow ray a vertex; inside the sphere every light point but those on the vertex's own
// triangle is in front of it, so nearly one.
TEST(RayCounts, BackwardCountsDepthGuardClosestRaysPerPathInAFurnace) {
  for (const char* scene : {"scenes/furnace_passive.json", "scenes/furnace_self_absorption.json"})
    for (int depth : {1, 3}) {
      test::RenderResult r = render(scene, "backward", depth);
      const double paths = r.scene.camera.width * r.scene.camera.height * 4.0 * 2;
      const double closest = r.counters.closest_rays, shadow = r.counters.shadow_rays;
      if (depth == 1) {
        EXPECT_EQ(closest, paths) << scene;
      } else {  // a ray slipping through a crack between the tessellation's triangles ends a path
        EXPECT_NEAR(closest, depth * paths, 1e-4 * depth * paths) << scene;
      }
      EXPECT_LE(shadow, closest) << scene;
      if (std::string(scene).find("passive") != std::string::npos) {
        EXPECT_GT(shadow, 0.97 * closest) << scene;
      } else {  // a box: light points on the vertex's own face are not in front of it
        EXPECT_GT(shadow, 0.5 * closest) << scene;
      }
      std::printf("[ rays     ] %s, max depth %d: %.0f paths, %.0f closest, %.0f shadow rays\n",
                  scene, depth, paths, closest, shadow);
    }
}

// Under --max-depth N a furnace's camera path traces N + 1 closest-hit rays (emission seen after
// 0 … N scatterings) and next-event estimation N shadow rays (from the vertices 0 … N − 1), nearly
// one a vertex as above; the depth guard cuts nothing.
TEST(RayCounts, BackwardUnderADepthCapTracesCapPlusOneRaysPerPath) {
  for (int cap : {0, 2}) {
    test::RenderSettings s;
    s.passes = 2;
    s.spectral = false;
    s.integrator_settings.spp = 4;
    s.integrator_settings.max_depth = cap;
    test::RenderResult r = render_scene(test::source_path("scenes/furnace_passive.json"), s);
    const double paths = r.scene.camera.width * r.scene.camera.height * 4.0 * 2;
    EXPECT_NEAR(r.counters.closest_rays, (cap + 1) * paths, 1e-4 * (cap + 1) * paths) << cap;
    EXPECT_LE(r.counters.shadow_rays, cap * paths) << cap;
    EXPECT_GE(r.counters.shadow_rays, 0.97 * cap * paths) << cap;
    EXPECT_EQ(r.counters.depth_guard.cut, 0) << cap;
  }
}

// Every integrator counts at least one closest-hit ray per path it starts (camera paths and
// photons) and some shadow rays; photon mapping a gather query per pixel and pass at least.
TEST(RayCounts, EveryIntegratorCountsItsPaths) {
  for (const char* integrator : {"backward", "forward", "photon"}) {
    test::RenderResult r = render("scenes/cornell_box.json", integrator, 1 << 18, 1);
    const double pixels = r.scene.camera.width * r.scene.camera.height;
    const double photons = 2.0 * (1 << 14);
    const std::string name = integrator;
    const double least = name == "backward"  ? 2 * pixels
                         : name == "forward" ? photons
                                             : 2 * pixels + photons;
    EXPECT_GE(r.counters.closest_rays, least) << integrator;
    EXPECT_GT(r.counters.shadow_rays, 0) << integrator;
    if (name == "photon") {
      EXPECT_GE(r.counters.gather_queries, 2 * pixels);
    }
  }
}

// add_count's (low, high) words: 4096 work items adding 2^21 + 1 each wrap the low word twice.
TEST(RayCounts, SumsCarryIntoTheHighWord) {
  const char* source = R"(
#include "geometry/hit_point.h"
__kernel void count(__global uint* words, uint n) { add_count(words, n); }
)";
  ClContext& cl = test::test_device();
  cl::Program program = build_program(cl, assemble_kernel_source_text(source, "count_test.cl"),
                                      test::test_kernel_defines(), "count_test.cl");
  cl::Kernel kernel(program, "count");
  std::vector<cl_uint> words(2, 0);
  cl::Buffer buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                    words.size() * sizeof(cl_uint), words.data());
  const cl_uint n = (1u << 21) + 1;
  const size_t items = 4096;
  kernel.setArg(0, buffer);
  kernel.setArg(1, n);
  cl.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NullRange);
  cl.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, words.size() * sizeof(cl_uint), words.data());
  const unsigned long long total = words[0] + (static_cast<unsigned long long>(words[1]) << 32);
  EXPECT_EQ(total, static_cast<unsigned long long>(n) * items);
  EXPECT_EQ(words[1], 2u);
}
