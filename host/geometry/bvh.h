#pragma once
// A wide BVH built by Embree's rtcBuildBVH (SAH, KASHA_BVH_WIDTH children per node) and flattened
// into the KBvhNode / KBvhLeaf layouts that the OpenCL traversal reads; triangles are reordered
// into leaf order.
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

struct FlatBvh {
  std::vector<KBvhNode> nodes;       // node 0 is the root, always an interior node
  std::vector<KBvhLeaf> leaves;      // precomputed triangles of each leaf
  std::vector<KTriangle> triangles;  // leaf order; KTriangle::prim keeps the scene index
  int depth = 0;                     // levels of interior nodes
};

FlatBvh build_bvh(const std::vector<KTriangle>& triangles);

}  // namespace kasha
