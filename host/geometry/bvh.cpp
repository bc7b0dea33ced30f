#include "geometry/bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "geometry/embree_device.h"

namespace kasha {

namespace {

// Embree's builder hands us nodes and leaves through callbacks; they live in its thread-local
// allocator until the RTCBVH is released, by which time they are flattened.
struct BuildNode {
  virtual ~BuildNode() = default;
  RTCBounds bounds{};
};
struct InnerNode : BuildNode {
  BuildNode* child[2] = {nullptr, nullptr};
  RTCBounds child_bounds[2]{};
};
struct LeafNode : BuildNode {
  unsigned first = 0, count = 0;  // into the leaf-ordered primitive id list
  unsigned* ids = nullptr;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
  (void)child_count;  // always 2: maxBranchingFactor = 2
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16);
  return static_cast<BuildNode*>(new (mem) InnerNode);
}

void set_children(void* node, void** children, unsigned int count, void*) {
  auto* inner = static_cast<InnerNode*>(static_cast<BuildNode*>(node));
  for (unsigned i = 0; i < count; ++i) inner->child[i] = static_cast<BuildNode*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
  auto* inner = static_cast<InnerNode*>(static_cast<BuildNode*>(node));
  for (unsigned i = 0; i < count; ++i) inner->child_bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count,
                  void*) {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(LeafNode), 16);
  auto* leaf = new (mem) LeafNode;
  leaf->ids = static_cast<unsigned*>(rtcThreadLocalAlloc(alloc, count * sizeof(unsigned), 16));
  leaf->count = static_cast<unsigned>(count);
  for (size_t i = 0; i < count; ++i) leaf->ids[i] = prims[i].primID;
  return static_cast<BuildNode*>(leaf);
}

RTCBounds leaf_bounds(const LeafNode& leaf, const std::vector<KTriangle>& tris) {
  RTCBounds b{INFINITY, INFINITY, INFINITY, 0, -INFINITY, -INFINITY, -INFINITY, 0};
  for (unsigned i = 0; i < leaf.count; ++i) {
    const KTriangle& t = tris[leaf.ids[i]];
    for (const float* v : {t.v0, t.v1, t.v2}) {
      b.lower_x = std::min(b.lower_x, v[0]), b.upper_x = std::max(b.upper_x, v[0]);
      b.lower_y = std::min(b.lower_y, v[1]), b.upper_y = std::max(b.upper_y, v[1]);
      b.lower_z = std::min(b.lower_z, v[2]), b.upper_z = std::max(b.upper_z, v[2]);
    }
  }
  return b;
}

void store_bounds(KBvhNode& n, const RTCBounds& b) {
  n.lo[0] = b.lower_x, n.lo[1] = b.lower_y, n.lo[2] = b.lower_z;
  n.hi[0] = b.upper_x, n.hi[1] = b.upper_y, n.hi[2] = b.upper_z;
}

void flatten(const BuildNode* node, const RTCBounds& bounds, const std::vector<KTriangle>& in,
             FlatBvh& out, int depth) {
  out.depth = std::max(out.depth, depth);
  int index = static_cast<int>(out.nodes.size());
  out.nodes.push_back(KBvhNode{});
  if (auto* leaf = dynamic_cast<const LeafNode*>(node)) {
    KBvhNode& n = out.nodes[index];
    store_bounds(n, bounds);
    n.offset = static_cast<int>(out.triangles.size());
    n.count = static_cast<int>(leaf->count);
    for (unsigned i = 0; i < leaf->count; ++i) out.triangles.push_back(in[leaf->ids[i]]);
    return;
  }
  auto* inner = static_cast<const InnerNode*>(node);
  store_bounds(out.nodes[index], bounds);
  flatten(inner->child[0], inner->child_bounds[0], in, out, depth + 1);
  out.nodes[index].offset = static_cast<int>(out.nodes.size());
  out.nodes[index].count = 0;
  flatten(inner->child[1], inner->child_bounds[1], in, out, depth + 1);
}

}  // namespace

FlatBvh build_bvh(const std::vector<KTriangle>& triangles) {
  FlatBvh out;
  if (triangles.empty()) return out;
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const KTriangle& t = triangles[i];
    RTCBuildPrimitive p{};
    p.lower_x = std::min({t.v0[0], t.v1[0], t.v2[0]});
    p.lower_y = std::min({t.v0[1], t.v1[1], t.v2[1]});
    p.lower_z = std::min({t.v0[2], t.v1[2], t.v2[2]});
    p.upper_x = std::max({t.v0[0], t.v1[0], t.v2[0]});
    p.upper_y = std::max({t.v0[1], t.v1[1], t.v2[1]});
    p.upper_z = std::max({t.v0[2], t.v1[2], t.v2[2]});
    p.geomID = 0;
    p.primID = static_cast<unsigned>(i);
    prims.push_back(p);
  }

  RTCBVH bvh = rtcNewBVH(embree_device());
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // SAH binning, no spatial splits
  args.maxBranchingFactor = 2;
  args.maxDepth = KASHA_BVH_MAX_DEPTH;
  args.minLeafSize = 1;
  args.maxLeafSize = 4;
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  args.splitPrimitive = nullptr;
  auto* root = static_cast<BuildNode*>(rtcBuildBVH(&args));
  if (!root) {
    rtcReleaseBVH(bvh);
    throw Error("Embree: BVH build failed (error " +
                std::to_string(rtcGetDeviceError(embree_device())) + ")");
  }
  // The root's bounds are not reported through a parent; a lone leaf's come from its triangles.
  RTCBounds root_bounds;
  if (auto* leaf = dynamic_cast<LeafNode*>(root)) {
    root_bounds = leaf_bounds(*leaf, triangles);
  } else {
    auto* inner = static_cast<InnerNode*>(root);
    const RTCBounds &a = inner->child_bounds[0], &b = inner->child_bounds[1];
    root_bounds = {std::min(a.lower_x, b.lower_x), std::min(a.lower_y, b.lower_y),
                   std::min(a.lower_z, b.lower_z), 0,
                   std::max(a.upper_x, b.upper_x), std::max(a.upper_y, b.upper_y),
                   std::max(a.upper_z, b.upper_z), 0};
  }
  out.nodes.reserve(2 * triangles.size());
  out.triangles.reserve(triangles.size());
  flatten(root, root_bounds, triangles, out, 1);
  rtcReleaseBVH(bvh);
  if (out.triangles.size() != triangles.size()) throw Error("Embree: BVH lost primitives");
  return out;
}

}  // namespace kasha
