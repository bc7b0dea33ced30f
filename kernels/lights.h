/* Next-event estimation: emitting triangles chosen in proportion to their power (a CDF over the
 * emitting triangles), then a point on the chosen one: uniform in the solid angle it subtends from
 * the shading point (Arvo 1995, as pbrt-v4 does) when that angle lies between
 * KASHA_MIN_SPHERICAL_SOLID_ANGLE and KASHA_MAX_SPHERICAL_SOLID_ANGLE, uniform in area otherwise. Since a triangle's power is its area
 * times pi times its emitter's band-integrated radiance, the area density of a light point,
 * p(triangle)/area, depends only on the emitter: emitter_area_pdf[e]. */
#ifndef KASHA_LIGHTS_H
#define KASHA_LIGHTS_H

#include "bvh_traversal.h"
#include "hit_point.h"
#include "sampling.h"
#include "scene_view.h"

typedef struct {
  float3 position;
  float3 normal; /* front side */
  int emitter;
  float eps; /* the point's rounding bound along the normal (hit_point.h's surface_offset) */
} LightPoint;

/* The emitting triangle whose CDF step holds u (the first with light_cdf > u). */
inline int choose_light(const __global float* light_cdf, int light_count, float u) {
  int lo = 0, hi = light_count - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (light_cdf[mid] > u) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

inline LightPoint sample_light(const __global KTriangle* tris, const __global int* light_tri,
                               const __global float* light_cdf, int light_count, float u0, float u1, float u2) {
  int lo = choose_light(light_cdf, light_count, u0);
  const __global KTriangle* t = &tris[light_tri[lo]];
  float3 v0 = load_float3(t->v0), e1 = load_float3(t->v1) - v0, e2 = load_float3(t->v2) - v0;
  float2 b = sample_triangle(u1, u2);
  LightPoint p;
  p.position = v0 + b.x * e1 + b.y * e2;
  p.normal = normalize(cross(e1, e2));
  p.emitter = t->emitter;
  p.eps = surface_offset(v0, v0 + e1, v0 + e2, 1.0f - b.x - b.y, b.x, b.y, p.normal);
  return p;
}

/* Solid-angle density of reaching a light point at distance `dist` whose normal makes cos_light
 * with the direction back to the shading point. */
inline float light_pdf_solid_angle(const __global float* emitter_area_pdf, int emitter, float dist, float cos_light) {
  return cos_light > 0.0f ? emitter_area_pdf[emitter] * dist * dist / cos_light : 0.0f;
}


/* Solid angle of the triangle (v0, v1, v2) seen from p (Van Oosterom & Strackee 1983). */
inline float triangle_solid_angle(float3 p, float3 v0, float3 v1, float3 v2) {
  float3 a = normalize(v0 - p), b = normalize(v1 - p), c = normalize(v2 - p);
  return 2.0f * atan2(fabs(dot(a, cross(b, c))), 1.0f + dot(a, b) + dot(a, c) + dot(b, c));
}

inline bool spherical_sampling(float solid_angle) {
  return solid_angle > KASHA_MIN_SPHERICAL_SOLID_ANGLE && solid_angle < KASHA_MAX_SPHERICAL_SOLID_ANGLE;
}

/* A direction from p uniform in the solid angle `omega` of the triangle (Arvo 1995): u.x picks the
 * area u.x·Ω of a sub-triangle a-b-c' (c' on the arc a-c), u.y a point on the arc from b to c'.
 * The angle α at a enters through its cosine and sine alone, and Ω is the solid angle the caller
 * already has, so one sincos is all the trigonometry. */
inline float3 sample_spherical_triangle(float3 p, float3 v0, float3 v1, float3 v2, float omega, float2 u) {
  float3 a = normalize(v0 - p), b = normalize(v1 - p), c = normalize(v2 - p);
  float3 n_ab = normalize(cross(a, b)), n_ca = normalize(cross(c, a));
  float cos_alpha = -dot(n_ab, n_ca), sin_alpha = length(cross(n_ab, n_ca));
  float cos_area, sin_area = sincos(KASHA_PI + u.x * omega, &cos_area); /* of A' + π */
  float sin_phi = sin_area * cos_alpha - cos_area * sin_alpha;
  float cos_phi = cos_area * cos_alpha + sin_area * sin_alpha;
  float k1 = cos_phi + cos_alpha;
  float k2 = sin_phi - sin_alpha * dot(a, b);
  float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
  cos_bp = clamp(cos_bp, -1.0f, 1.0f);
  float sin_bp = sqrt(fmax(0.0f, 1.0f - cos_bp * cos_bp));
  float3 cp = cos_bp * a + sin_bp * normalize(c - dot(c, a) * a);
  float cos_t = 1.0f - u.y * (1.0f - dot(cp, b));
  float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
  return cos_t * b + sin_t * normalize(cp - dot(cp, b) * b);
}

/* A light point for next-event estimation at x, with the solid-angle density of having sampled
 * its direction (0 when the sample failed). u.x picks the triangle and, rescaled to the part of
 * [0, 1) that picked it, goes on with u.y to pick the point: the 2-D sample stays stratified over
 * all the emitting triangles together (a quad lamp's two triangles included). */
inline LightPoint sample_light_from(const SceneView* s, float3 x, float2 u, float* pdf) {
  int lo = choose_light(s->light_cdf, s->light_count, u.x);
  float below = lo > 0 ? s->light_cdf[lo - 1] : 0.0f, width = s->light_cdf[lo] - below;
  u.x = width > 0.0f ? clamp((u.x - below) / width, 0.0f, 0.99999994f) : 0.5f;
  const __global KTriangle* t = &s->tris[s->light_tri[lo]];
  float3 v0 = load_float3(t->v0), v1 = load_float3(t->v1), v2 = load_float3(t->v2);
  float3 cr = cross(v1 - v0, v2 - v0);
  float area = 0.5f * length(cr);
  LightPoint p;
  p.normal = normalize(cr);
  p.emitter = t->emitter;
  float area_pdf = s->emitter_area_pdf[t->emitter]; /* p(triangle) / area */
  float omega = triangle_solid_angle(x, v0, v1, v2);
  *pdf = 0.0f;
  if (spherical_sampling(omega)) {
    float3 w = sample_spherical_triangle(x, v0, v1, v2, omega, u);
    float along = dot(p.normal, w);
    float dist = along != 0.0f ? dot(p.normal, v0 - x) / along : 0.0f;
    p.position = x + dist * w;
    /* Found along a ray from x: its rounding grows with x and the distance too. */
    p.eps = surface_offset(v0, v1, v2, 1.0f, 1.0f, 1.0f, p.normal) +
            KASHA_GAMMA(16) * (dot(fabs(p.normal), fabs(x)) + dist);
    if (dist > 0.0f && isfinite(dist)) *pdf = area_pdf * area / omega;
  } else {
    float2 b = sample_triangle(u.x, u.y);
    p.position = v0 + b.x * (v1 - v0) + b.y * (v2 - v0);
    p.eps = surface_offset(v0, v1, v2, 1.0f - b.x - b.y, b.x, b.y, p.normal);
    float3 to = p.position - x;
    float d2 = dot(to, to), cos_l = -dot(p.normal, to) / sqrt(d2);
    if (cos_l > 0.0f) *pdf = area_pdf * d2 / cos_l;
  }
  return p;
}

/* The solid-angle density with which sample_light_from at x would pick the point y on leaf
 * triangle `tri` (front side seen, cos_light > 0), for multiple importance sampling. */
inline float light_pdf_from(const SceneView* s, int tri, float3 x, float3 y, float cos_light) {
  const __global KTriangle* t = &s->tris[tri];
  float3 v0 = load_float3(t->v0), v1 = load_float3(t->v1), v2 = load_float3(t->v2);
  float area_pdf = s->emitter_area_pdf[t->emitter];
  float omega = triangle_solid_angle(x, v0, v1, v2);
  if (spherical_sampling(omega)) return area_pdf * 0.5f * length(cross(v1 - v0, v2 - v0)) / omega;
  float3 to = y - x;
  return cos_light > 0.0f ? area_pdf * dot(to, to) / cos_light : 0.0f;
}

#endif
