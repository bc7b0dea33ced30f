#pragma once
// The OpenCL head of the light sampling kernel tests (sphere lights, the light BVH): lights.h and
// SAMPLE_LIGHT_AT_X_IN, the draw they all start from, to put before a test's kernels.

namespace kasha::test {

// In a kernel taking KASHA_SCENE_PARAMS, the point x_in and numbers u: the scene s, the work item
// i, the point x and the light point p that sample_light_from draws at x from u[2i] and u[2i + 1],
// of density pdf.
inline constexpr const char* kLightSampleKernelHead = R"(
#include "lights/lights.h"
#define SAMPLE_LIGHT_AT_X_IN()  \
  KASHA_SCENE_VIEW(s);          \
  size_t i = get_global_id(0);  \
  float3 x = vload3(0, x_in);   \
  float pdf;                    \
  LightPoint p = sample_light_from(&s, x, vload2(i, u), &pdf)
)";

}  // namespace kasha::test
