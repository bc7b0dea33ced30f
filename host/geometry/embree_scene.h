#pragma once
// Embree's own intersector over the same triangles: the host reference the OpenCL traversal is
// tested against, and the yard-stick the traversal benchmark compares with.
#include <embree3/rtcore.h>

#include <vector>

#include "geometry/alpha_cutouts.h"
#include "geometry/instances.h"
#include "shared/shared_types.h"

namespace kasha {

class EmbreeScene {
 public:
  // Scene order: primID = index. With `alpha`, hits pass its cut-outs' test as the kernels' do.
  // With `instances`, each object is one Embree scene placed by Embree's instances, and hits
  // name their instance as the kernels do (geometry/instances.h's kernel_instances).
  explicit EmbreeScene(const std::vector<KTriangle>& triangles,
                       const AlphaCutouts& alpha = AlphaCutouts(),
                       const SceneInstances& instances = SceneInstances());
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  KHit intersect(const KRay& ray) const;
  bool occluded(const KRay& ray) const;
  // All rays, spread over the host's hardware threads.
  void intersect_all(const std::vector<KRay>& rays, std::vector<KHit>& hits) const;
  void occluded_all(const std::vector<KRay>& rays, std::vector<int>& occluded) const;

 private:
  RTCGeometry triangle_geometry(size_t first, size_t count, const std::vector<KTriangle>& tris);

  RTCScene scene_ = nullptr;
  std::vector<RTCScene> objects_;     // per object, when there are instances
  std::vector<int> instance_first_;   // per Embree instance ID: its object's first triangle
  int own_instance_ = -1;             // KHit::instance of the scene's own triangles
  std::vector<KTriangle> triangles_;  // kept for the alpha test, with its tables
  AlphaCutouts alpha_;
  std::vector<AlphaTables> tables_;  // per geometry, offset to its first triangle
};

}  // namespace kasha
