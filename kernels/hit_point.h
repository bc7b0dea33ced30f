/* The closest hit along a ray, with what every integrator asks of it: the point, the geometric
 * normal, the normal on the side the ray came from, and the triangle's material and emitter. */
#ifndef KASHA_HIT_POINT_H
#define KASHA_HIT_POINT_H

#include "bvh_traversal.h"
#include "scene_view.h"

typedef struct {
  float3 x;      /* the hit point */
  float3 n;      /* geometric normal, (v1 − v0) × (v2 − v0) normalized: the front side */
  float3 ns;     /* the normal on the side the ray arrived from */
  bool front;    /* the ray arrived on the front side */
  float t;       /* distance along the (unit) direction */
  int material;
  int emitter;   /* -1: the triangle does not emit */
  int tri;       /* the triangle, in leaf order */
} HitPoint;

inline bool intersect_scene(const SceneView* s, float3 org, float3 dir, HitPoint* h) {
  float t, u, v;
  int hit = bvh_closest(s->nodes, s->tris, org, dir, 0.0f, INFINITY, &t, &u, &v);
  if (hit < 0) return false;
  const __global KTriangle* tri = &s->tris[hit];
  float3 v0 = load_float3(tri->v0);
  h->n = normalize(cross(load_float3(tri->v1) - v0, load_float3(tri->v2) - v0));
  h->front = dot(h->n, dir) < 0.0f;
  h->ns = h->front ? h->n : -h->n;
  h->x = org + t * dir;
  h->t = t;
  h->material = tri->material;
  h->emitter = tri->emitter;
  h->tri = hit;
  return true;
}

/* Whether anything blocks the segment from x (offset off its surface along ns) to dist along wi,
 * short of the far end's own offset. */
inline bool segment_occluded(const SceneView* s, float3 x, float3 ns, float3 wi, float dist) {
  return bvh_occluded(s->nodes, s->tris, x + ns * s->ray_eps, wi, 0.0f, dist - 2.0f * s->ray_eps);
}

#endif
