// The OpenCL runtime: kernel assembly, build failures with their log, packed tables and the
// by-value scene parameters' layout on both sides.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <numeric>

#include "kernel_harness.h"
#include "opencl/kernel_program.h"
#include "opencl/upload.h"
#include "shared/shared_types.h"
#include "test_support.h"

using namespace kasha;

TEST(OpenCl, IncludesAreInlinedOnce) {
  std::string src = assemble_kernel_source("debug/debug_render.cl");
  EXPECT_EQ(src.find("#include \""), std::string::npos);
  // shared_types.h, reached through several headers, appears once.
  const std::string node = "typedef struct {\n  float bounds[6][KASHA_BVH_WIDTH];";
  size_t first = src.find(node);
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(src.find(node, first + 1), std::string::npos);
}

TEST(OpenCl, BuildFailureCarriesTheBuildLog) {
  ClContext cl(0);
  std::string msg = test::error_of([&] {
    build_program(cl, "__kernel void broken(__global float* x) { x[0] = undefined_name; }",
                  {{"KASHA_BINS", "4"}}, "broken.cl");
  });
  EXPECT_NE(msg.find("OpenCL kernel build failed for broken.cl"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-D KASHA_BINS=4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("undefined_name"), std::string::npos) << msg;  // from the compiler's log
}

TEST(OpenCl, BadDeviceIndexIsOneClearLine) {
  std::string msg = test::error_of([] { ClContext cl(99); });
  EXPECT_NE(msg.find("--device 99: no such OpenCL device"), std::string::npos) << msg;
}

// Tables of odd sizes land at multiples of kTableAlign, in order, and read back as given; the
// large one goes through the CPU device's huge-page path.
TEST(OpenCl, TablesUploadAtAlignedOffsets) {
  for (size_t large : {size_t(0), size_t(5) << 20}) {
    ClContext& cl = test::test_device();
    std::vector<int> a(3);
    std::iota(a.begin(), a.end(), 1);
    std::vector<float> empty, b(large / sizeof(float) + 7);
    std::iota(b.begin(), b.end(), 0.5f);
    std::vector<KTriangle> c(5);
    c[4].prim = 42;
    std::uint64_t at[4] = {99, 99, 99, 99};
    cl::Buffer buffer = upload_tables(cl, {host_table(a, at[0]), host_table(empty, at[1]),
                                           host_table(b, at[2]), host_table(c, at[3])});
    EXPECT_EQ(at[0], 0u);
    EXPECT_EQ(at[1], kTableAlign);
    EXPECT_EQ(at[2], kTableAlign);
    EXPECT_EQ(at[3], (kTableAlign + b.size() * sizeof(float) + kTableAlign - 1) / kTableAlign *
                         kTableAlign);
    std::vector<unsigned char> back(at[3] + c.size() * sizeof(KTriangle));
    cl.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, back.size(), back.data());
    EXPECT_EQ(0, std::memcmp(back.data(), a.data(), a.size() * sizeof(int)));
    EXPECT_EQ(0, std::memcmp(back.data() + at[2], b.data(), b.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(back.data() + at[3], c.data(), c.size() * sizeof(KTriangle)));
  }
}

// KSceneParams passed by value reads the same on the device as the host wrote it.
TEST(OpenCl, SceneParamsLayoutIsTheHosts) {
  test::TestKernel kernel(R"(
#include "shared/shared_types.h"
__kernel void params(KSceneParams p, __global float* out) {
  out[0] = (float)sizeof(KSceneParams);
  out[1] = p.camera.up[2];
  out[2] = (float)p.nodes;
  out[3] = (float)p.normals;
  out[4] = (float)p.light_count;
  out[5] = p.bin_nm;
  out[6] = (float)p.light_sources;
}
)",
                          "params_test.cl", "params");
  KSceneParams p{};
  p.camera.up[2] = 0.25f;
  p.nodes = 256;
  p.normals = 1u << 20;
  p.light_count = 3;
  p.bin_nm = 5.0f;
  p.light_sources = 2;
  kernel.scalar(0, p);
  kernel.output(1, 7);
  kernel.run(1);
  EXPECT_EQ(kernel.read(1), (std::vector<float>{sizeof(KSceneParams), 0.25f, 256.0f, 1048576.0f,
                                                3.0f, 5.0f, 2.0f}));
}
