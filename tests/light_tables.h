#pragma once
// Scene tables for kernel tests of light sampling, as DeviceScene uploads them: triangles in leaf
// order, some of them emitting (radiance 1 in every bin), the power CDF and the light BVH over
// them; and pbrt-v4's importance in double on the host, the reference for the BVH's choice.
#include <Eigen/Dense>
#include <vector>

#include "opencl/device.h"
#include "render/light_bvh.h"
#include "shared/shared_types.h"

namespace kasha::test {

struct LightTables {
  KSceneParams params{};
  cl::Buffer buffer;  // argument 1 of a kernel taking KASHA_SCENE_PARAMS
  std::vector<int> light_tri;
  std::vector<float> light_cdf;
  LightBvh bvh;
};

// `emitting`: leaf-order indices of the emitting triangles, ascending, of powers `power` (> 0);
// each triangle's `emitter` indexes the emitters, of which there are `emitters`.
LightTables light_tables(const std::vector<KTriangle>& tris, const std::vector<int>& emitting,
                         const std::vector<double>& power, int emitters);

// pbrt-v4's LightBounds::Importance at x without a normal (θe = π/2), in double.
double reference_importance(const KLightNode& node, const Eigen::Vector3d& x);

// The probability that the BVH's descent at x reaches emitting triangle j, in double (by the
// children's power at a node where neither has importance).
double reference_pick(const LightBvh& bvh, int j, const Eigen::Vector3d& x);

}  // namespace kasha::test
