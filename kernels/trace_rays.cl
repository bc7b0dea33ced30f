/* Batch ray queries: what tests compare with Embree and the benchmark times. */
#include "bvh_traversal.h"

__kernel void trace_closest(__global const KBvhNode* nodes, __global const KTriangle* tris,
                            __global const KRay* rays, __global KHit* hits, int count) {
  int i = get_global_id(0);
  if (i >= count) return;
  KRay r = rays[i];
  float3 org = (float3)(r.org[0], r.org[1], r.org[2]);
  float3 dir = (float3)(r.dir[0], r.dir[1], r.dir[2]);
  float t, u = 0.0f, v = 0.0f;
  int leaf = bvh_closest(nodes, tris, org, dir, r.tmin, r.tmax, &t, &u, &v);
  KHit h;
  h.t = t;
  h.prim = leaf >= 0 ? tris[leaf].prim : -1;
  h.u = u;
  h.v = v;
  hits[i] = h;
}

__kernel void trace_occluded(__global const KBvhNode* nodes, __global const KTriangle* tris,
                             __global const KRay* rays, __global int* occluded, int count) {
  int i = get_global_id(0);
  if (i >= count) return;
  KRay r = rays[i];
  float3 org = (float3)(r.org[0], r.org[1], r.org[2]);
  float3 dir = (float3)(r.dir[0], r.dir[1], r.dir[2]);
  occluded[i] = bvh_occluded(nodes, tris, org, dir, r.tmin, r.tmax) ? 1 : 0;
}
