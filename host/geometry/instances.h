#pragma once
// Object instancing as the geometry layer holds it (pbrt-v4's ObjectBegin / ObjectInstance;
// docs/formats.md#instances): an object is a range of the scene's triangles, stored once; an
// instance places it by an affine transform. The scene's own triangles are those before every
// object's.
#include <array>
#include <vector>

#include "shared/shared_types.h"

namespace kasha {

struct ObjectRange {
  int first_triangle = 0, triangle_count = 0;  // in scene order
};

// Row-major 3 × 4 affine matrix: world_from_object, and its inverse.
using Affine = std::array<double, 12>;

struct Placement {
  int object = 0;
  Affine world_from_object{};
};

struct SceneInstances {
  std::vector<ObjectRange> objects;
  std::vector<Placement> placements;
  int world_triangles = 0;  // the scene's own triangles: scene order [0, world_triangles)
  bool empty() const { return placements.empty(); }
};

Affine inverse_affine(const Affine& m);
// The box of an object's triangles in object space: lo x, y, z then hi x, y, z (lo > hi: empty).
std::array<float, 6> object_box(const std::vector<KTriangle>& triangles, const ObjectRange& r);
// m·p (a point) and m·d (a direction), in float as the kernels do it.
void affine_point(const float* m, const float* p, float* out);
void affine_direction(const float* m, const float* d, float* out);
// The kernel record of a placement (root set by the BVH build).
KInstance kernel_instance(const Placement& p);
// The kernels' instances in their numbering (KHit::instance): the scene's own triangles first,
// under the identity (object -1), when it has any; then the placements. Empty without placements.
std::vector<KInstance> kernel_instances(const SceneInstances& instances);
// The triangle as placed in the world, its winding kept to its front: under a mirroring
// transform v1 and v2 swap (and with them the barycentrics u and v).
KTriangle placed_triangle(const KTriangle& t, const KInstance& instance);

}  // namespace kasha
