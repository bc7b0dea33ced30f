#pragma once
// Batch closest-hit and any-hit queries through the OpenCL traversal kernel: what the tests
// compare with Embree and the benchmark times.
#include <vector>

#include "geometry/bvh.h"
#include "opencl/device.h"

namespace kasha {

class ClTraversal {
 public:
  ClTraversal(ClContext& cl, const FlatBvh& bvh);
  std::vector<KHit> closest(const std::vector<KRay>& rays);
  std::vector<int> occluded(const std::vector<KRay>& rays);

 private:
  template <typename Out>
  std::vector<Out> run(cl::Kernel& kernel, const std::vector<KRay>& rays);

  ClContext& cl_;
  cl::Buffer nodes_, triangles_;
  cl::Kernel closest_, occluded_;
};

}  // namespace kasha
