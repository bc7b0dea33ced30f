#pragma once
// The gather of photon mapping on the host: a kd-tree (nanoflann) over one pass's photons, and
// for each visible point the sum of K·Φ (kernels/vertex_factor.h, the same code the kernels use)
// over the photons within its radius on the same side of the surface, on the host's threads.
#include <cstddef>
#include <vector>

#include "vertex_factor.h"

namespace kasha {

// Photons count only within this fraction of the radius of a visible point's tangent plane.
constexpr float kGatherSlab = KASHA_GATHER_SLAB;

struct GatherResult {
  std::vector<double> flux;  // pixels × rows: Σ K·Φ over the photons found
  std::vector<int> found;    // pixels: photons found
};

class PhotonKdTree {
 public:
  PhotonKdTree(const float* photons, size_t count, int floats_per_photon);
  ~PhotonKdTree();
  PhotonKdTree(const PhotonKdTree&) = delete;
  PhotonKdTree& operator=(const PhotonKdTree&) = delete;

  // Gathers for every pixel with a valid visible point, within radius[pixel].
  GatherResult gather(const float* visible_points, int vp_floats, size_t pixels,
                      const std::vector<double>& radius, const VertexFactorLayout& layout) const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace kasha
