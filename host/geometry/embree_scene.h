#pragma once
// Embree's own intersector over the same triangles: the host reference the OpenCL traversal is
// tested against, and the yard-stick the traversal benchmark compares with.
#include <embree3/rtcore.h>

#include <vector>

#include "geometry/alpha_cutouts.h"
#include "shared/shared_types.h"

namespace kasha {

class EmbreeScene {
 public:
  // Scene order: primID = index. With `alpha`, hits pass its cut-outs' test as the kernels' do.
  explicit EmbreeScene(const std::vector<KTriangle>& triangles,
                       const AlphaCutouts& alpha = AlphaCutouts());
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  KHit intersect(const KRay& ray) const;
  bool occluded(const KRay& ray) const;
  // All rays, spread over the host's hardware threads.
  void intersect_all(const std::vector<KRay>& rays, std::vector<KHit>& hits) const;
  void occluded_all(const std::vector<KRay>& rays, std::vector<int>& occluded) const;

 private:
  RTCScene scene_ = nullptr;
  std::vector<KTriangle> triangles_;  // kept for the alpha test, with its tables
  AlphaCutouts alpha_;
  AlphaTables tables_{};
};

}  // namespace kasha
