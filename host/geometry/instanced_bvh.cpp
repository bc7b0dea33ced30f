#include "geometry/instanced_bvh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace kasha {

namespace {

// The world box of an instance: its object's box's eight corners placed.
RTCBuildPrimitive instance_box(const KInstance& k, const float lo[3], const float hi[3],
                               unsigned id) {
  RTCBuildPrimitive p{};
  p.lower_x = p.lower_y = p.lower_z = INFINITY;
  p.upper_x = p.upper_y = p.upper_z = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const float c[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                        corner & 4 ? hi[2] : lo[2]};
    float w[3];
    affine_point(k.world_from_object, c, w);
    // Widened by a few ulps: the box must hold what the float transform of the ray meets.
    for (int a = 0; a < 3; ++a) {
      const float pad = 4e-7f * (std::abs(w[a]) + 1e-30f);
      (&p.lower_x)[a] = std::min((&p.lower_x)[a], w[a] - pad);
      (&p.upper_x)[a] = std::max((&p.upper_x)[a], w[a] + pad);
    }
  }
  p.geomID = 0;
  p.primID = id;
  return p;
}

}  // namespace

FlatBvh build_instanced_bvh(const std::vector<KTriangle>& triangles,
                            const SceneInstances& instances) {
  if (instances.empty()) return build_bvh(triangles);
  FlatBvh out;
  // The scene's own triangles as instance 0 under the identity, then the placements.
  const std::vector<ObjectRange>& ranges = instances.objects;
  out.instances = kernel_instances(instances);

  // Object boxes once, instance boxes from them; the top-level tree first, so node 0 is its root.
  std::vector<std::array<float, 6>> boxes;
  for (const ObjectRange& r : ranges) boxes.push_back(object_box(triangles, r));
  boxes.push_back(object_box(triangles, {0, instances.world_triangles}));
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(out.instances.size());
  for (size_t i = 0; i < out.instances.size(); ++i) {
    const int object = out.instances[i].object;
    const auto& b = object < 0 ? boxes.back() : boxes[object];
    if (!(b[0] <= b[3])) continue;  // an object without triangles is met by no ray
    prims.push_back(instance_box(out.instances[i], b.data(), b.data() + 3, unsigned(i)));
  }
  int top_depth = 0;
  build_tree(
      prims, 1, [](const unsigned* ids, unsigned) { return ~static_cast<int>(ids[0]); }, out,
      top_depth);

  // Each object's tree (and the scene's own) once, whatever its instance count.
  std::vector<int> roots(ranges.size() + 1);
  int deepest = 0, d = 0;
  roots.back() = append_triangle_bvh(triangles, 0, instances.world_triangles, out, d);
  deepest = std::max(deepest, d);
  for (size_t o = 0; o < ranges.size(); ++o) {
    roots[o] =
        append_triangle_bvh(triangles, ranges[o].first_triangle, ranges[o].triangle_count, out, d);
    deepest = std::max(deepest, d);
  }
  for (KInstance& k : out.instances) k.root = k.object < 0 ? roots.back() : roots[k.object];
  out.depth = top_depth + deepest;
  if (out.depth > KASHA_BVH_MAX_DEPTH)  // the kernels' one stack holds both levels
    throw Error("Embree: two-level BVH of depth " + std::to_string(out.depth) + " (at most " +
                std::to_string(KASHA_BVH_MAX_DEPTH) + ")");
  if (out.triangles.size() != triangles.size()) throw Error("Embree: BVH lost primitives");
  return out;
}

}  // namespace kasha
