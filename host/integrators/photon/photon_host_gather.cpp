#include "integrators/photon/photon_host_gather.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nanoflann.hpp>

#include "core/parallel_for.h"
#include "shared/photon_layout.h"
#include "shared/volume_gather.h"

namespace kasha {

namespace {
// nanoflann's dataset adaptor: the photons' positions, copied out of the records so the build
// walks a compact array.
struct PhotonCloud {
  const float* data;
  size_t count;
  int stride;
  std::vector<float> positions;
  size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(size_t i, size_t dim) const { return positions[3 * i + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>,
                                                 PhotonCloud, 3, uint32_t>;
}  // namespace

struct PhotonKdTree::Impl {
  PhotonCloud cloud;
  Tree tree;
  Impl(const float* photons, size_t count, int stride)
      : cloud{photons, count, stride, positions_of(photons, count, stride)},
        tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
  static std::vector<float> positions_of(const float* photons, size_t count, int stride) {
    std::vector<float> p(3 * count);
    for (size_t i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k) p[3 * i + k] = photons[i * stride + k];
    return p;
  }
};

PhotonKdTree::PhotonKdTree(const float* photons, size_t count, int floats_per_photon)
    : impl_(new Impl(photons, count, floats_per_photon)) {}

PhotonKdTree::~PhotonKdTree() {
  delete impl_;
}

// The scattering vertices of the path a photon and a visible point make: the camera path's
// bounces (1 + them in the valid flag under a cap), the photon's, and the merged vertex.
static int merged_path_depth(const float* vp, const float* photon) {
  int32_t photon_bounces;
  std::memcpy(&photon_bounces, photon + KASHA_PHOTON_DEPTH, sizeof photon_bounces);
  return static_cast<int>(vp[KASHA_VP_VALID]) - 1 + photon_bounces + 1;
}

GatherResult PhotonKdTree::gather(const float* vps, int vp_floats, size_t pixels,
                                  const std::vector<double>& radius, const VertexFactorLayout& L,
                                  int depth_cap) const {
  GatherResult out;
  out.flux.assign(pixels * L.rows, 0.0);
  out.found.assign(pixels, 0);
  const int stride = impl_->cloud.stride;
  const float* photons = impl_->cloud.data;
  parallel_for(pixels, [&](size_t begin, size_t end) {
    std::vector<std::pair<uint32_t, float>> matches;
    for (size_t px = begin; px < end; ++px) {
      const float* vp = vps + px * vp_floats;
      if (vp[KASHA_VP_VALID] == 0.0f || impl_->cloud.count == 0) continue;
      const float r = static_cast<float>(radius[px]), r2 = r * r;
      impl_->tree.radiusSearch(vp, r2, matches, nanoflann::SearchParams(32, 0.0f, false));
      double* rows = &out.flux[px * L.rows];
      int found = 0;
      const bool in_medium = record_in_medium(vp);
      for (const auto& [index, dist2] : matches) {
        const float* ph = photons + static_cast<size_t>(index) * stride;
        double scale = 1;
        if (in_medium) {
          // In a medium: the medium's photons, through the phase function (volume_gather.h).
          if (!record_in_medium(ph)) continue;
          scale = volume_gather_weight(vp, ph, L.bins, L.rows, L.fluorescent, r);
        } else {
          // Same side of the surface, roughly the same orientation, and close to the visible
          // point's tangent plane: no leaks through thin walls, around corners, or from a nearby
          // parallel surface (a lamp just under a ceiling). A medium's photons face nothing.
          if (ph[3] * vp[3] + ph[4] * vp[4] + ph[5] * vp[5] < 0.5f) continue;
          const float off =
              (ph[0] - vp[0]) * vp[3] + (ph[1] - vp[1]) * vp[4] + (ph[2] - vp[2]) * vp[5];
          if (std::abs(off) > kGatherSlab * r) continue;
        }
        if (depth_cap >= 0 && merged_path_depth(vp, ph) > depth_cap) continue;
        ++found;
        vf_apply_scaled(L, vp, ph + KASHA_PHOTON_POWER, scale, rows);
      }
      out.found[px] = found;
    }
  });
  return out;
}

void HostGather::take_inputs(const PassInputs& inputs) {
  visible_points_ = inputs.visible_points;
  radius_.assign(inputs.radius.begin(), inputs.radius.end());
}

void HostGather::gather(std::vector<float>& records, size_t count, ChunkResult& c) const {
  sort_by_key(records, count);
  PhotonKdTree tree(records.data(), count, photon_floats_);
  GatherResult found =
      tree.gather(visible_points_.data(), vp_floats_, pixels_, radius_, layout_, depth_cap_);
  for (size_t i = 0; i < c.flux.size(); ++i) c.flux[i] += found.flux[i];
  for (size_t p = 0; p < c.found.size(); ++p) c.found[p] += found.found[p];
}

void HostGather::sort_by_key(std::vector<float>& records, size_t count) const {
  auto key = [&](size_t i) {
    const float* r = &records[i * photon_floats_];
    uint32_t index, depth;
    std::memcpy(&index, r + KASHA_PHOTON_INDEX, sizeof index);
    std::memcpy(&depth, r + KASHA_PHOTON_DEPTH, sizeof depth);
    return static_cast<uint64_t>(index) << 32 | depth;
  };
  std::vector<size_t> order(count);
  for (size_t i = 0; i < count; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  std::vector<float> sorted(count * photon_floats_);
  for (size_t i = 0; i < count; ++i)
    std::memcpy(&sorted[i * photon_floats_], &records[order[i] * photon_floats_],
                photon_floats_ * sizeof(float));
  records.swap(sorted);
}

}  // namespace kasha
