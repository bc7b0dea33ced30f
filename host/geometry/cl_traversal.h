#pragma once
// Batch closest-hit and any-hit queries through the OpenCL traversal kernel: what the tests
// compare with Embree and the benchmark times.
#include <vector>

#include "geometry/alpha_cutouts.h"
#include "geometry/bvh.h"
#include "opencl/device.h"

namespace kasha {

class ClTraversal {
 public:
  // With `alpha` (scene order), hits pass its cut-outs' test (built with KASHA_ALPHA).
  ClTraversal(ClContext& cl, const FlatBvh& bvh, const AlphaCutouts& alpha = AlphaCutouts());
  std::vector<KHit> closest(const std::vector<KRay>& rays);
  std::vector<int> occluded(const std::vector<KRay>& rays);
  // Into the caller's vector, resized to the rays: a batch after the first of its size then
  // allocates nothing, on either side (what the benchmark times).
  void closest(const std::vector<KRay>& rays, std::vector<KHit>& hits);
  void occluded(const std::vector<KRay>& rays, std::vector<int>& occluded);

 private:
  template <typename Out>
  void run(cl::Kernel& kernel, const std::vector<KRay>& rays, std::vector<Out>& out);

  ClContext& cl_;
  cl::Buffer nodes_, leaves_, instances_, triangles_;
  cl::Buffer texcoords_, textures_, values_,
      ops_;                    // the alpha tables, leaf order (one entry without)
  cl::Buffer rays_, results_;  // kept between batches, grown when a batch needs more
  size_t ray_capacity_ = 0, result_bytes_ = 0;
  cl::Kernel closest_, occluded_;
};

}  // namespace kasha
