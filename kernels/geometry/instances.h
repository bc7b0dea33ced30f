/* Object instances (shared_types.h: KInstance; docs/formats.md#instances): the affine maps a ray
 * enters an instance by, and the world-space triangle and normals of a hit inside one. Only
 * compiled where the scene has instances (KASHA_INSTANCES). */
#ifndef KASHA_INSTANCES_H
#define KASHA_INSTANCES_H

#include "shared/shared_types.h"

#ifndef KASHA_INSTANCES
#define KASHA_INSTANCES 0
#endif

/* m·p and m·d for a row-major 3 × 4 affine matrix. */
inline float3 affine_point(const __global float* m, float3 p) {
  return (float3)(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                  m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]);
}

inline float3 affine_direction(const __global float* m, float3 d) {
  return (float3)(m[0] * d.x + m[1] * d.y + m[2] * d.z, m[4] * d.x + m[5] * d.y + m[6] * d.z,
                  m[8] * d.x + m[9] * d.y + m[10] * d.z);
}

/* A normal carried from object to world space: by the inverse transpose, i.e. the transpose of
 * object_from_world's linear part (not normalised). */
inline float3 affine_normal(const __global float* object_from_world, float3 n) {
  const __global float* m = object_from_world;
  return (float3)(m[0] * n.x + m[4] * n.y + m[8] * n.z, m[1] * n.x + m[5] * n.y + m[9] * n.z,
                  m[2] * n.x + m[6] * n.y + m[10] * n.z);
}

#endif
