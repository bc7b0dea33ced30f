#pragma once
// A wide BVH built by Embree's rtcBuildBVH (SAH, KASHA_BVH_WIDTH children per node) and flattened
// into the KBvhNode / KBvhLeaf layouts that the OpenCL traversal reads; triangles are reordered
// into leaf order.
#include <embree3/rtcore.h>

#include <functional>
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

struct FlatBvh {
  std::vector<KBvhNode> nodes;       // node 0 is the root, always an interior node
  std::vector<KBvhLeaf> leaves;      // precomputed triangles of each leaf
  std::vector<KTriangle> triangles;  // leaf order; KTriangle::prim keeps the scene index
  // Two levels (geometry/instanced_bvh.h): node 0 roots the tree over these, each object's tree
  // follows; empty for one level.
  std::vector<KInstance> instances;
  int depth = 0;  // levels of interior nodes (both levels' together)
};

FlatBvh build_bvh(const std::vector<KTriangle>& triangles);

// The pieces that build_bvh and the instanced build share.
// A leaf's reference (~leaf, or ~instance at the top level) from its primitives' ids.
using LeafRef = std::function<int(const unsigned* ids, unsigned count)>;
// Embree's SAH build over `prims` (leaves of `leaf_size`), its nodes appended to out.nodes;
// returns the root's index, always an interior node (one that no ray enters when there are no
// primitives), and sets `depth`.
int build_tree(std::vector<RTCBuildPrimitive>& prims, int leaf_size, const LeafRef& leaf_ref,
               FlatBvh& out, int& depth);
// The tree over triangles [first, first + count), appended to `out` (leaves, leaf-order
// triangles); returns its root.
int append_triangle_bvh(const std::vector<KTriangle>& triangles, size_t first, size_t count,
                        FlatBvh& out, int& depth);

}  // namespace kasha
