#pragma once
// A binary BVH built by Embree's rtcBuildBVH (SAH) and flattened depth-first into the KBvhNode
// layout that the OpenCL traversal reads; triangles are reordered into leaf order.
#include <vector>

#include "shared_types.h"

namespace kasha {

struct FlatBvh {
  std::vector<KBvhNode> nodes;
  std::vector<KTriangle> triangles;  // leaf order; KTriangle::prim keeps the scene index
  int depth = 0;
};

FlatBvh build_bvh(const std::vector<KTriangle>& triangles);

}  // namespace kasha
