#pragma once
// The gather of photon mapping on the host (`--gather host`): a kd-tree (nanoflann) over a full
// store's photons, and for each visible point the sum of K·Φ (kernels/shared/vertex_factor.h, the
// same code the kernels use) over the photons within its radius on the same side of the surface, on
// the host's threads.
#include <cstddef>
#include <vector>

#include "render/pass_chunks.h"
#include "shared/vertex_factor.h"

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

  // Gathers for every pixel with a valid visible point, within radius[pixel]; under a
  // --max-depth cap (>= 0), only the photons that make a path of at most that many scattering
  // vertices with the visible point's camera path (kernels/photon/photon_gather.cl).
  GatherResult gather(const float* visible_points, int vp_floats, size_t pixels,
                      const std::vector<double>& radius, const VertexFactorLayout& layout,
                      int depth_cap = -1) const;

 private:
  struct Impl;
  Impl* impl_;
};

// A pass's host gathers: the visible points and radii copied from the device once a pass, and
// each full store's records gathered into a chunk's result.
class HostGather {
 public:
  HostGather(int photon_floats, int vp_floats, size_t pixels, const VertexFactorLayout& layout,
             int depth_cap)
      : photon_floats_(photon_floats),
        vp_floats_(vp_floats),
        pixels_(pixels),
        layout_(layout),
        depth_cap_(depth_cap) {}

  void take_inputs(const PassInputs& inputs);
  // Adds the gather of `count` records (read from the store) to `c`; reorders `records`.
  void gather(std::vector<float>& records, size_t count, ChunkResult& c) const;

 private:
  // The records in key order (photon index, bounce), as the device's gather takes them.
  void sort_by_key(std::vector<float>& records, size_t count) const;

  int photon_floats_, vp_floats_;
  size_t pixels_;
  VertexFactorLayout layout_;
  int depth_cap_;  // --max-depth's cap, or -1
  std::vector<float> visible_points_;
  std::vector<double> radius_;
};

}  // namespace kasha
