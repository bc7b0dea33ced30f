#pragma once
// The two-level BVH of a scene with instances: a top-level tree whose leaves are instances (the
// scene's own triangles being instance 0, under the identity), above one tree per object, each
// object's triangles stored once however often it is placed. The kernels' traversal
// (kernels/geometry/bvh_traversal.h, KASHA_INSTANCES) enters an instance by transforming the ray.
#include "geometry/bvh.h"
#include "geometry/instances.h"

namespace kasha {

// `triangles` in scene order; without placements, build_bvh's one level.
FlatBvh build_instanced_bvh(const std::vector<KTriangle>& triangles,
                            const SceneInstances& instances);

}  // namespace kasha
