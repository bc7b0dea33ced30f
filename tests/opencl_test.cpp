// The OpenCL runtime: kernel assembly, build failures with their log.
#include <gtest/gtest.h>

#include "opencl/kernel_program.h"
#include "test_support.h"

using namespace kasha;

TEST(OpenCl, IncludesAreInlinedOnce) {
  std::string src = assemble_kernel_source("debug_render.cl");
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
