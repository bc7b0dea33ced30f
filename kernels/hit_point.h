/* The closest hit along a ray, with what every integrator asks of it: the point, the geometric
 * normal, the normal on the side the ray came from, and the triangle's material and emitter. */
#ifndef KASHA_HIT_POINT_H
#define KASHA_HIT_POINT_H

#include "bvh_traversal.h"

typedef struct {
  float3 x;      /* the hit point */
  float3 n;      /* geometric normal, (v1 − v0) × (v2 − v0) normalized: the front side */
  float3 ns;     /* the normal on the side the ray arrived from */
  bool front;    /* the ray arrived on the front side */
  float t;       /* distance along the (unit) direction */
  int material;
  int emitter;   /* -1: the triangle does not emit */
} HitPoint;

inline bool intersect_scene(const __global KBvhNode* nodes, const __global KTriangle* tris, float3 org, float3 dir,
                            HitPoint* h) {
  float t, u, v;
  int hit = bvh_closest(nodes, tris, org, dir, 0.0f, INFINITY, &t, &u, &v);
  if (hit < 0) return false;
  const __global KTriangle* tri = &tris[hit];
  float3 v0 = load_float3(tri->v0);
  h->n = normalize(cross(load_float3(tri->v1) - v0, load_float3(tri->v2) - v0));
  h->front = dot(h->n, dir) < 0.0f;
  h->ns = h->front ? h->n : -h->n;
  h->x = org + t * dir;
  h->t = t;
  h->material = tri->material;
  h->emitter = tri->emitter;
  return true;
}

#endif
