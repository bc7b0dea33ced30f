/* Batch ray queries: what tests compare with Embree and the benchmark times. The alpha tables
 * (leaf order) are read only when built with KASHA_ALPHA. */
#include "geometry/bvh_traversal.h"

#define KASHA_TRACE_PARAMS                                                                                   \
  __global const KBvhNode *nodes, __global const KBvhLeaf *leaves, __global const KInstance *instances,      \
      __global const KTriangle *tris, __global const KTexcoords *texcoords, __global const KTexture *textures, \
      __global const float *values, __global const KTexOp *ops, __global const KRay *rays

__kernel void trace_closest(KASHA_TRACE_PARAMS, __global KHit* hits, int count) {
  int i = get_global_id(0);
  if (i >= count) return;
  const __global KRay* r = &rays[i];
  AlphaTables alpha = {tris, texcoords, textures, values, ops};
  BvhTables bvh = {nodes, leaves, instances};
  float t, u = 0.0f, v = 0.0f;
  int inst;
  int leaf = bvh_closest(&bvh, &alpha, load_float3(r->org), load_float3(r->dir), r->tmin, r->tmax, &t, &u, &v,
                         &inst);
  KHit h;
  h.t = t;
  h.prim = leaf >= 0 ? tris[leaf].prim : -1;
  h.u = u;
  h.v = v;
  h.instance = leaf >= 0 ? inst : -1;
  hits[i] = h;
}

/* Same parameters as trace_closest, so the host sets both alike. */
__kernel void trace_occluded(KASHA_TRACE_PARAMS, __global int* occluded, int count) {
  int i = get_global_id(0);
  if (i >= count) return;
  const __global KRay* r = &rays[i];
  AlphaTables alpha = {tris, texcoords, textures, values, ops};
  BvhTables bvh = {nodes, leaves, instances};
  occluded[i] = bvh_occluded(&bvh, &alpha, load_float3(r->org), load_float3(r->dir), r->tmin, r->tmax) ? 1 : 0;
}
