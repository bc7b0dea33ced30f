#include "geometry/bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/error.h"
#include "geometry/embree_device.h"

namespace kasha {

namespace {

constexpr int W = KASHA_BVH_WIDTH;
constexpr int L = KASHA_BVH_LEAF_SIZE;

// Embree's builder hands us nodes and leaves through callbacks; they live in its thread-local
// allocator until the RTCBVH is released, by which time they are flattened.
struct BuildNode {
  virtual ~BuildNode() = default;
};
struct InnerNode : BuildNode {
  unsigned count = 0;
  BuildNode* child[W] = {};
  RTCBounds child_bounds[W]{};
};
struct LeafNode : BuildNode {
  unsigned count = 0;
  unsigned ids[L] = {};  // scene indices of its triangles
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(InnerNode), 16);
  auto* node = new (mem) InnerNode;
  node->count = child_count;  // at most maxBranchingFactor = W
  return static_cast<BuildNode*>(node);
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
  leaf->count = static_cast<unsigned>(count);  // at most maxLeafSize = L; flatten_leaf checks
  for (size_t i = 0; i < count && i < L; ++i) leaf->ids[i] = prims[i].primID;
  return static_cast<BuildNode*>(leaf);
}

// Slot i of node n: the child's box and reference.
void set_slot(KBvhNode& n, int i, const RTCBounds& b, int ref) {
  const float lo[3] = {b.lower_x, b.lower_y, b.lower_z}, hi[3] = {b.upper_x, b.upper_y, b.upper_z};
  for (int k = 0; k < 3; ++k) n.bounds[2 * k][i] = lo[k], n.bounds[2 * k + 1][i] = hi[k];
  n.child[i] = ref;
}

KBvhNode empty_node() {
  KBvhNode n{};
  const RTCBounds none{INFINITY, INFINITY, INFINITY, 0, -INFINITY, -INFINITY, -INFINITY, 0};
  for (int i = 0; i < W; ++i) set_slot(n, i, none, 0);
  return n;
}

// Appends a leaf's triangles in leaf order and their precomputed form; returns its reference.
int flatten_leaf(const unsigned* ids, unsigned count, const std::vector<KTriangle>& in,
                 FlatBvh& out) {
  if (count > L) throw Error("Embree: BVH leaf of " + std::to_string(count) + " triangles");
  KBvhLeaf block{};
  for (int i = 0; i < L; ++i) block.tri[i] = -1;
  for (unsigned i = 0; i < count; ++i) {
    const KTriangle& t = in[ids[i]];
    for (int k = 0; k < 3; ++k) {
      block.v0[k][i] = t.v0[k];
      block.e1[k][i] = t.v1[k] - t.v0[k];
      block.e2[k][i] = t.v2[k] - t.v0[k];
    }
    block.tri[i] = static_cast<int>(out.triangles.size());
    out.triangles.push_back(t);
  }
  out.leaves.push_back(block);
  return ~static_cast<int>(out.leaves.size() - 1);
}

// Depth first: a node's children follow it, leaves in the order the traversal meets them.
int flatten(const BuildNode* node, const LeafRef& leaf_ref, FlatBvh& out, int depth, int& deepest) {
  if (auto* leaf = dynamic_cast<const LeafNode*>(node)) return leaf_ref(leaf->ids, leaf->count);
  auto* inner = static_cast<const InnerNode*>(node);
  deepest = std::max(deepest, depth);
  int index = static_cast<int>(out.nodes.size());
  out.nodes.push_back(empty_node());
  for (unsigned i = 0; i < inner->count; ++i) {
    int ref = flatten(inner->child[i], leaf_ref, out, depth + 1, deepest);
    set_slot(out.nodes[index], static_cast<int>(i), inner->child_bounds[i], ref);
  }
  return index;
}

RTCBounds prims_bounds(const std::vector<RTCBuildPrimitive>& prims) {
  RTCBounds b{INFINITY, INFINITY, INFINITY, 0, -INFINITY, -INFINITY, -INFINITY, 0};
  for (const RTCBuildPrimitive& p : prims) {
    b.lower_x = std::min(b.lower_x, p.lower_x), b.upper_x = std::max(b.upper_x, p.upper_x);
    b.lower_y = std::min(b.lower_y, p.lower_y), b.upper_y = std::max(b.upper_y, p.upper_y);
    b.lower_z = std::min(b.lower_z, p.lower_z), b.upper_z = std::max(b.upper_z, p.upper_z);
  }
  return b;
}

}  // namespace

int build_tree(std::vector<RTCBuildPrimitive>& prims, int leaf_size, const LeafRef& leaf_ref,
               FlatBvh& out, int& depth) {
  const int root_index = static_cast<int>(out.nodes.size());
  out.nodes.push_back(empty_node());  // for no primitives, a root that no ray enters
  depth = prims.empty() ? 0 : 1;
  if (prims.empty()) return root_index;
  const size_t count = prims.size();
  // Owns the builder's nodes until they are flattened, also when flattening throws.
  std::unique_ptr<RTCBVHTy, void (*)(RTCBVH)> bvh(rtcNewBVH(embree_device()), rtcReleaseBVH);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // SAH binning, no spatial splits
  args.maxBranchingFactor = W;
  args.maxDepth = KASHA_BVH_MAX_DEPTH;
  // A leaf costs one vector test whether it holds 1 or L triangles: SAH counts leaves so, and a
  // set that fits one leaf is not split further just to fill a node's slots.
  args.sahBlockSize = leaf_size;
  args.minLeafSize = leaf_size;
  args.maxLeafSize = leaf_size;
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = bvh.get();
  args.primitives = prims.data();
  args.primitiveCount = count;
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  args.splitPrimitive = nullptr;
  const RTCBounds all = prims_bounds(prims);
  auto* root = static_cast<BuildNode*>(rtcBuildBVH(&args));
  if (!root) {
    throw Error("Embree: BVH build failed (error " +
                std::to_string(rtcGetDeviceError(embree_device())) + ")");
  }
  if (auto* leaf = dynamic_cast<LeafNode*>(root)) {
    // A lone leaf hangs from a root of one child, so the traversal always starts at a node.
    set_slot(out.nodes[root_index], 0, all, leaf_ref(leaf->ids, leaf->count));
  } else {
    out.nodes.pop_back();
    flatten(root, leaf_ref, out, 1, depth);
  }
  if (depth > KASHA_BVH_MAX_DEPTH)  // the kernels' stack would overflow
    throw Error("Embree: BVH of depth " + std::to_string(depth) + " (at most " +
                std::to_string(KASHA_BVH_MAX_DEPTH) + ")");
  return root_index;
}

RTCBuildPrimitive triangle_box(const KTriangle& t, unsigned id) {
  RTCBuildPrimitive p{};
  p.lower_x = std::min({t.v0[0], t.v1[0], t.v2[0]});
  p.lower_y = std::min({t.v0[1], t.v1[1], t.v2[1]});
  p.lower_z = std::min({t.v0[2], t.v1[2], t.v2[2]});
  p.upper_x = std::max({t.v0[0], t.v1[0], t.v2[0]});
  p.upper_y = std::max({t.v0[1], t.v1[1], t.v2[1]});
  p.upper_z = std::max({t.v0[2], t.v1[2], t.v2[2]});
  p.geomID = 0;
  p.primID = id;
  return p;
}

int append_triangle_bvh(const std::vector<KTriangle>& triangles, size_t first, size_t count,
                        FlatBvh& out, int& depth) {
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(count);
  for (size_t i = first; i < first + count; ++i)
    prims.push_back(triangle_box(triangles[i], static_cast<unsigned>(i)));
  return build_tree(
      prims, L,
      [&](const unsigned* ids, unsigned n) { return flatten_leaf(ids, n, triangles, out); }, out,
      depth);
}

FlatBvh build_bvh(const std::vector<KTriangle>& triangles) {
  FlatBvh out;
  out.nodes.reserve(triangles.size() / (2 * L) + 1);
  out.leaves.reserve(triangles.size() / (L / 2) + 1);
  out.triangles.reserve(triangles.size());
  append_triangle_bvh(triangles, 0, triangles.size(), out, out.depth);
  if (out.triangles.size() != triangles.size()) throw Error("Embree: BVH lost primitives");
  return out;
}

}  // namespace kasha
