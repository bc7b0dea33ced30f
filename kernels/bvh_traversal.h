/* Closest-hit and any-hit queries over the flattened BVH built by Embree on the host
 * (shared_types.h: KBvhNode, KTriangle). Triangles use the Möller–Trumbore test. */
#ifndef KASHA_BVH_TRAVERSAL_H
#define KASHA_BVH_TRAVERSAL_H

#include "shared_types.h"

inline float3 load_float3(const __global float* p) { return (float3)(p[0], p[1], p[2]); }

/* Slab test; the far distance is widened by 2 ulps-ish (Ize 2013) so rounding never culls a box the
 * ray grazes. Returns the entry distance, or INFINITY on a miss. */
inline float box_entry(const __global KBvhNode* n, float3 org, float3 inv_dir, float tmin, float tmax) {
  float3 t0 = (load_float3(n->lo) - org) * inv_dir;
  float3 t1 = (load_float3(n->hi) - org) * inv_dir;
  float3 tn = fmin(t0, t1), tf = fmax(t0, t1);
  float enter = fmax(fmax(tn.x, tn.y), fmax(tn.z, tmin));
  float leave = fmin(fmin(tf.x, tf.y), fmin(tf.z, tmax)) * 1.0000004f;
  return enter <= leave ? enter : INFINITY;
}

/* Möller–Trumbore. On a hit inside [tmin, tmax] writes t and the barycentrics of v1 and v2. */
inline bool intersect_triangle(const __global KTriangle* tri, float3 org, float3 dir, float tmin, float tmax,
                               float* t, float* u, float* v) {
  float3 v0 = load_float3(tri->v0);
  float3 e1 = load_float3(tri->v1) - v0;
  float3 e2 = load_float3(tri->v2) - v0;
  float3 p = cross(dir, e2);
  float det = dot(e1, p);
  if (det == 0.0f) return false;
  float inv = 1.0f / det;
  float3 s = org - v0;
  float bu = dot(s, p) * inv;
  if (bu < 0.0f || bu > 1.0f) return false;
  float3 q = cross(s, e1);
  float bv = dot(dir, q) * inv;
  if (bv < 0.0f || bu + bv > 1.0f) return false;
  float tt = dot(e2, q) * inv;
  if (!(tt >= tmin && tt <= tmax)) return false;
  *t = tt;
  *u = bu;
  *v = bv;
  return true;
}

/* Ordered stack traversal. Closest hit: returns the leaf-order index of the nearest triangle in
 * [tmin, tmax] (or -1) with its t and barycentrics. With `any_hit` it stops at the first triangle
 * found (shadow rays); the compiler specializes each caller, as the flag is a constant there. */
inline int bvh_traverse(const __global KBvhNode* nodes, const __global KTriangle* tris, float3 org, float3 dir,
                        float tmin, float tmax, bool any_hit, float* t_hit, float* u_hit, float* v_hit) {
  float3 inv_dir = 1.0f / dir;
  int best = -1;
  float best_t = tmax;
  if (box_entry(&nodes[0], org, inv_dir, tmin, best_t) == INFINITY) return -1;
  int stack[KASHA_BVH_MAX_DEPTH];
  int sp = 0;
  int node = 0;
  for (;;) {
    const __global KBvhNode* n = &nodes[node];
    if (n->count > 0) {
      for (int i = n->offset; i < n->offset + n->count; ++i) {
        float t, u, v;
        if (intersect_triangle(&tris[i], org, dir, tmin, best_t, &t, &u, &v)) {
          best = i;
          best_t = t;
          *u_hit = u;
          *v_hit = v;
          if (any_hit) {
            *t_hit = t;
            return i;
          }
        }
      }
    } else {
      int left = node + 1, right = n->offset;
      float tl = box_entry(&nodes[left], org, inv_dir, tmin, best_t);
      float tr = box_entry(&nodes[right], org, inv_dir, tmin, best_t);
      if (tl != INFINITY && tr != INFINITY) {
        /* Visit the nearer child first; the other waits on the stack. */
        stack[sp++] = tl <= tr ? right : left;
        node = tl <= tr ? left : right;
        continue;
      }
      if (tl != INFINITY || tr != INFINITY) {
        node = tl != INFINITY ? left : right;
        continue;
      }
    }
    if (sp == 0) break;
    node = stack[--sp];
  }
  *t_hit = best_t;
  return best;
}

inline int bvh_closest(const __global KBvhNode* nodes, const __global KTriangle* tris, float3 org, float3 dir,
                       float tmin, float tmax, float* t_hit, float* u_hit, float* v_hit) {
  return bvh_traverse(nodes, tris, org, dir, tmin, tmax, false, t_hit, u_hit, v_hit);
}

inline bool bvh_occluded(const __global KBvhNode* nodes, const __global KTriangle* tris, float3 org, float3 dir,
                         float tmin, float tmax) {
  float t, u, v;
  return bvh_traverse(nodes, tris, org, dir, tmin, tmax, true, &t, &u, &v) >= 0;
}

#endif
