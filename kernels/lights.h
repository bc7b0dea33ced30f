/* Next-event estimation: emitting triangles chosen in proportion to their power (a CDF over the
 * emitting triangles), a uniform point on the chosen one. Since a triangle's power is its area
 * times pi times its emitter's band-integrated radiance, the area density of a light point,
 * p(triangle)/area, depends only on the emitter: emitter_area_pdf[e]. */
#ifndef KASHA_LIGHTS_H
#define KASHA_LIGHTS_H

#include "bvh_traversal.h"
#include "sampling.h"

typedef struct {
  float3 position;
  float3 normal; /* front side */
  int emitter;
} LightPoint;

inline LightPoint sample_light(const __global KTriangle* tris, const __global int* light_tri,
                               const __global float* light_cdf, int light_count, float u0, float u1, float u2) {
  int lo = 0, hi = light_count - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (light_cdf[mid] > u0) hi = mid;
    else lo = mid + 1;
  }
  const __global KTriangle* t = &tris[light_tri[lo]];
  float3 v0 = load_float3(t->v0), e1 = load_float3(t->v1) - v0, e2 = load_float3(t->v2) - v0;
  float2 b = sample_triangle(u1, u2);
  LightPoint p;
  p.position = v0 + b.x * e1 + b.y * e2;
  p.normal = normalize(cross(e1, e2));
  p.emitter = t->emitter;
  return p;
}

/* Solid-angle density of reaching a light point at distance `dist` whose normal makes cos_light
 * with the direction back to the shading point. */
inline float light_pdf_solid_angle(const __global float* emitter_area_pdf, int emitter, float dist, float cos_light) {
  return cos_light > 0.0f ? emitter_area_pdf[emitter] * dist * dist / cos_light : 0.0f;
}

#endif
