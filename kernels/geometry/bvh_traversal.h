/* Closest-hit and any-hit queries over the 8-wide BVH built by Embree on the host (shared_types.h:
 * KBvhNode, KBvhLeaf). One float8 expression tests a node's eight child boxes, another a leaf's
 * eight triangles (Möller–Trumbore on precomputed edges): PoCL runs each work-item's traversal
 * loop as scalar code, so the vector types are what puts the CPU's AVX units to work. */
#ifndef KASHA_BVH_TRAVERSAL_H
#define KASHA_BVH_TRAVERSAL_H

#include "geometry/instances.h"
#include "shared/alpha_test.h"
#include "shared/shared_types.h"

/* Some shape has an alpha cut-out: candidate hits pass its test (shared/alpha_test.h). Without
 * one, the traversal is the same code as before alpha existed. */
#ifndef KASHA_ALPHA
#define KASHA_ALPHA 0
#endif

#if KASHA_BVH_WIDTH != 8 || KASHA_BVH_LEAF_SIZE != 8
#error "bvh_traversal.h tests eight children and eight triangles at a time"
#endif

inline float3 load_float3(const __global float* p) { return (float3)(p[0], p[1], p[2]); }

/* The BVH's tables. With KASHA_INSTANCES, node 0 roots the top-level tree, whose leaves are
 * instances (~k), each rooting its object's tree: one stack serves both levels. */
typedef struct {
  const __global KBvhNode* nodes;
  const __global KBvhLeaf* leaves;
  const __global KInstance* instances; /* read only with KASHA_INSTANCES */
} BvhTables;

/* A lane mask (-1 where true) as bits 0-7. */
inline int lane_bits(int8 m) {
  return (m.s0 & 1) | (m.s1 & 2) | (m.s2 & 4) | (m.s3 & 8) | (m.s4 & 16) | (m.s5 & 32) | (m.s6 & 64) | (m.s7 & 128);
}

inline int lowest_bit(int bits) { return 31 - clz(bits & -bits); }

/* The ray as every node test uses it: origin and reciprocal direction splatted, and for each axis
 * the row of KBvhNode::bounds holding the near planes (0: lo, 1: hi). */
typedef struct {
  float8 ox, oy, oz, ix, iy, iz;
  int nx, ny, nz;
} BvhRay;

inline BvhRay bvh_ray(float3 org, float3 dir) {
  float3 inv = 1.0f / dir;
  BvhRay r;
  r.ox = (float8)(org.x), r.oy = (float8)(org.y), r.oz = (float8)(org.z);
  r.ix = (float8)(inv.x), r.iy = (float8)(inv.y), r.iz = (float8)(inv.z);
  r.nx = inv.x < 0.0f, r.ny = inv.y < 0.0f, r.nz = inv.z < 0.0f;
  return r;
}

/* The ray a traversal is at: in world space, or in the object space of instance `inst` (entered
 * when the stack held `inst_sp` entries: popping below them leaves it). */
typedef struct {
  BvhRay r;
  float3 org, dir;
  int inst, inst_sp;
} BvhWalk;

inline void bvh_walk_world(BvhWalk* w, float3 org, float3 dir) {
  w->org = org, w->dir = dir;
  w->r = bvh_ray(org, dir);
  w->inst = -1, w->inst_sp = 0;
}

#if KASHA_INSTANCES
/* Into instance k at stack height sp: the ray in its object's space (the direction keeps its
 * length, so distances are the same numbers); returns its object's root. */
inline int bvh_enter(const BvhTables* b, BvhWalk* w, int k, int sp) {
  const __global KInstance* in = &b->instances[k];
  w->org = affine_point(in->object_from_world, w->org);
  w->dir = affine_direction(in->object_from_world, w->dir);
  w->r = bvh_ray(w->org, w->dir);
  w->inst = k, w->inst_sp = sp;
  return in->root;
}
#endif

/* The child boxes' slab test: entry distances, and which boxes [tmin, tmax] enters. Near and far
 * planes by the direction's sign, so an unused slot's inverted box is never entered; a NaN (0·inf:
 * the ray lies in a box's plane) leaves the bound it would set alone, keeping the box. The far
 * distance is widened by 2 ulps-ish (Ize 2013) so rounding never culls a box the ray grazes. */
inline int node_hits(const __global KBvhNode* n, const BvhRay* r, float tmin, float tmax, float8* enter) {
  const __global float8* b = (const __global float8*)n->bounds;
  float8 tnx = (b[r->nx] - r->ox) * r->ix, tfx = (b[1 - r->nx] - r->ox) * r->ix;
  float8 tny = (b[2 + r->ny] - r->oy) * r->iy, tfy = (b[3 - r->ny] - r->oy) * r->iy;
  float8 tnz = (b[4 + r->nz] - r->oz) * r->iz, tfz = (b[5 - r->nz] - r->oz) * r->iz;
  float8 e = (float8)(tmin), l = (float8)(tmax);
  e = tnx > e ? tnx : e;
  e = tny > e ? tny : e;
  e = tnz > e ? tnz : e;
  l = tfx < l ? tfx : l;
  l = tfy < l ? tfy : l;
  l = tfz < l ? tfz : l;
  *enter = e;
  return lane_bits(e <= l * 1.0000004f);
}

/* Möller–Trumbore on a leaf's triangles: the slots hit inside [tmin, tmax], with t and the
 * barycentrics of v1 and v2. Unused slots (zero edges) and edge-on triangles have det == 0. */
inline int leaf_hits(const __global KBvhLeaf* leaf, float3 org, float3 dir, float tmin, float tmax, float8* t,
                     float8* u, float8* v) {
  const __global float8* f = (const __global float8*)leaf;
  float8 v0x = f[0], v0y = f[1], v0z = f[2];
  float8 e1x = f[3], e1y = f[4], e1z = f[5];
  float8 e2x = f[6], e2y = f[7], e2z = f[8];
  float8 dx = (float8)(dir.x), dy = (float8)(dir.y), dz = (float8)(dir.z);
  /* p = dir × e2, det = e1 · p */
  float8 px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
  float8 det = e1x * px + e1y * py + e1z * pz;
  float8 inv = 1.0f / det;
  float8 sx = (float8)(org.x) - v0x, sy = (float8)(org.y) - v0y, sz = (float8)(org.z) - v0z;
  float8 bu = (sx * px + sy * py + sz * pz) * inv;
  /* q = s × e1 */
  float8 qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  float8 bv = (dx * qx + dy * qy + dz * qz) * inv;
  float8 tt = (e2x * qx + e2y * qy + e2z * qz) * inv;
  int8 ok = (det != 0.0f) & (bu >= 0.0f) & (bu <= 1.0f) & (bv >= 0.0f) & (bu + bv <= 1.0f) & (tt >= tmin) &
            (tt <= tmax);
  *t = tt;
  *u = bu;
  *v = bv;
  return lane_bits(ok);
}

/* Starts fetching every cache line of a child the traversal will visit: the misses of several
 * children then overlap instead of each stalling the ray in turn (PoCL on a CPU; elsewhere the
 * builtin may not exist and nothing is done). */
inline void prefetch_child(const __global KBvhNode* nodes, const __global KBvhLeaf* leaves, int ref) {
#if defined(__has_builtin) && (defined(__x86_64__) || defined(__aarch64__))
#if __has_builtin(__builtin_prefetch)
  if (ref >= 0) {
    const __global char* p = (const __global char*)&nodes[ref];
    for (int k = 0; k < (int)sizeof(KBvhNode); k += 64) __builtin_prefetch(p + k);
  } else {
    const __global char* p = (const __global char*)&leaves[~ref];
    for (int k = 0; k < (int)sizeof(KBvhLeaf); k += 64) __builtin_prefetch(p + k);
  }
#endif
#endif
}

/* Pushes the children of `n` whose boxes the ray enters (`bits`), keeping the entries pushed now
 * sorted far to near, and pops the nearest: returns the child to visit next. */
inline int push_children(const __global KBvhNode* nodes, const __global KBvhLeaf* leaves, const __global KBvhNode* n,
                         int bits, float8 enter, int* stack, float* stack_t, int* sp) {
  float e[KASHA_BVH_WIDTH];
  vstore8(enter, 0, e);
  int base = *sp, top = *sp;
  do {
    int i = lowest_bit(bits);
    bits &= bits - 1;
    int child = n->child[i];
    prefetch_child(nodes, leaves, child);
    float t = e[i];
    int j = top++;
    for (; j > base && stack_t[j - 1] < t; --j) stack[j] = stack[j - 1], stack_t[j] = stack_t[j - 1];
    stack[j] = child;
    stack_t[j] = t;
  } while (bits);
  *sp = top - 1;
  return stack[top - 1];
}

/* Whether leaf triangle `tri`'s candidate hit at (u, v) survives its shape's alpha test. */
inline bool alpha_candidate(const AlphaTables* alpha, int tri, float u, float v, float3 org, float3 dir) {
  float ray[6] = {org.x, org.y, org.z, dir.x, dir.y, dir.z};
  return alpha_keeps(alpha, tri, u, v, ray);
}

/* Ordered stack traversal for the closest hit: returns the leaf-order index of the nearest
 * triangle in [tmin, tmax] (or -1) with its t and barycentrics, and the instance it was met in
 * (-1 without instances). The stack keeps each waiting child's entry distance, so one farther than
 * the best hit so far is dropped when popped. With KASHA_ALPHA, a candidate that fails its alpha
 * test is passed over (`alpha` is read only then). */
inline int bvh_closest(const BvhTables* b, const AlphaTables* alpha, float3 org, float3 dir, float tmin, float tmax,
                       float* t_hit, float* u_hit, float* v_hit, int* inst_hit) {
  BvhWalk w;
  bvh_walk_world(&w, org, dir);
  int best = -1;
  float best_t = tmax;
  *inst_hit = -1;
  int stack[KASHA_BVH_STACK];
  float stack_t[KASHA_BVH_STACK];
  int sp = 0;
  int node = 0;
  for (;;) {
    if (node >= 0) {
      const __global KBvhNode* n = &b->nodes[node];
      float8 enter;
      int bits = node_hits(n, &w.r, tmin, best_t, &enter);
      if (bits) {
        node = push_children(b->nodes, b->leaves, n, bits, enter, stack, stack_t, &sp);
        continue;
      }
#if KASHA_INSTANCES
    } else if (w.inst < 0) {
      node = bvh_enter(b, &w, ~node, sp);
      continue;
#endif
    } else {
      const __global KBvhLeaf* leaf = &b->leaves[~node];
      float8 t8, u8, v8;
      int bits = leaf_hits(leaf, w.org, w.dir, tmin, best_t, &t8, &u8, &v8);
      if (bits) {
        float t[KASHA_BVH_LEAF_SIZE], u[KASHA_BVH_LEAF_SIZE], v[KASHA_BVH_LEAF_SIZE];
        vstore8(t8, 0, t), vstore8(u8, 0, u), vstore8(v8, 0, v);
        /* In slot order, a later one at the same distance winning, as a sequential test would. */
        do {
          int i = lowest_bit(bits);
          bits &= bits - 1;
          if (t[i] <= best_t) {
#if KASHA_ALPHA
            if (!alpha_candidate(alpha, leaf->tri[i], u[i], v[i], w.org, w.dir)) continue;
#endif
            best = leaf->tri[i];
            best_t = t[i];
            *u_hit = u[i];
            *v_hit = v[i];
            *inst_hit = w.inst;
          }
        } while (bits);
      }
    }
    do {
      if (sp == 0) {
        *t_hit = best_t;
        return best;
      }
      --sp;
    } while (stack_t[sp] > best_t);
#if KASHA_INSTANCES
    if (sp < w.inst_sp) bvh_walk_world(&w, org, dir); /* back at the top level */
#endif
    node = stack[sp];
  }
}

/* Whether some triangle of the leaf blocks [tmin, tmax]: with KASHA_ALPHA, one whose candidate
 * hit survives the alpha test. */
inline bool leaf_blocks(const __global KBvhLeaf* leaf, const AlphaTables* alpha, float3 org, float3 dir, float tmin,
                        float tmax) {
  float8 t8, u8, v8;
  int bits = leaf_hits(leaf, org, dir, tmin, tmax, &t8, &u8, &v8);
#if KASHA_ALPHA
  if (!bits) return false;
  float u[KASHA_BVH_LEAF_SIZE], v[KASHA_BVH_LEAF_SIZE];
  vstore8(u8, 0, u), vstore8(v8, 0, v);
  do {
    int i = lowest_bit(bits);
    bits &= bits - 1;
    if (alpha_candidate(alpha, leaf->tri[i], u[i], v[i], org, dir)) return true;
  } while (bits);
  return false;
#else
  return bits != 0;
#endif
}

/* Any hit in [tmin, tmax] (shadow rays), out at the first triangle found. Children go nearest
 * first here too: a blocker near the origin is found before the far side of the scene is
 * searched, which measured about 1.5× faster than slot order on shadow rays. */
inline bool bvh_occluded(const BvhTables* b, const AlphaTables* alpha, float3 org, float3 dir, float tmin,
                         float tmax) {
  BvhWalk w;
  bvh_walk_world(&w, org, dir);
  int stack[KASHA_BVH_STACK];
  float stack_t[KASHA_BVH_STACK];
  int sp = 0;
  int node = 0;
  for (;;) {
    if (node >= 0) {
      const __global KBvhNode* n = &b->nodes[node];
      float8 enter;
      int bits = node_hits(n, &w.r, tmin, tmax, &enter);
      if (bits) {
        node = push_children(b->nodes, b->leaves, n, bits, enter, stack, stack_t, &sp);
        continue;
      }
#if KASHA_INSTANCES
    } else if (w.inst < 0) {
      node = bvh_enter(b, &w, ~node, sp);
      continue;
#endif
    } else {
      if (leaf_blocks(&b->leaves[~node], alpha, w.org, w.dir, tmin, tmax)) return true;
    }
    if (sp == 0) return false;
    node = stack[--sp];
#if KASHA_INSTANCES
    if (sp < w.inst_sp) bvh_walk_world(&w, org, dir);
#endif
  }
}

#endif
