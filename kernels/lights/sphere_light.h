/* Next-event estimation of a sphere light (KASHA_SPHERE_LIGHTS): an emitting tessellated sphere
 * that the light BVH picks as one unit (host/render/light_bvh.cpp), sampled as pbrt-v4's
 * Sphere::Sample(ctx) does, by a direction uniform in the cone of its circumscribed sphere (radius
 * `radius` about `centre`: every vertex lies within it, so the mesh does too) seen from x, then
 * the first hit along it: the point is kept only where that hit is a front side of the sphere's
 * own triangles. Its density per solid angle is pick / Ω for every point of the sphere visible
 * from x (it is the first hit along the direction to it), which is all that multiple importance
 * sampling asks of it, and the mesh stays exact. From within the circumscribed sphere the cone is
 * the whole sphere of directions, Ω = 4π. */
#ifndef KASHA_SPHERE_LIGHT_H
#define KASHA_SPHERE_LIGHT_H

#include "geometry/hit_point.h"
#include "lights/light_point.h"
#include "materials/texture.h"
#include "sampling/sampling.h"

#ifndef KASHA_SPHERE_LIGHTS
#define KASHA_SPHERE_LIGHTS 0 /* some emitting sphere is sampled as one light */
#endif

#if KASHA_SPHERE_LIGHTS

/* The sphere light of emitting triangle j (its index in light_tri); radius 0: none. */
inline KSphereLight sphere_light_of(const SceneView* s, int j) { return s->light_spheres[j]; }

/* Whether emitting triangle j belongs to sphere light l (its record is l's: no two spheres share
 * both centre and radius, their triangles would coincide). */
inline bool on_sphere_light(const SceneView* s, int j, const KSphereLight* l) {
  const __global KSphereLight* m = &s->light_spheres[j];
  return m->radius == l->radius && m->centre[0] == l->centre[0] && m->centre[1] == l->centre[1] &&
         m->centre[2] == l->centre[2];
}

/* 1 − cos θmax of the cone the sphere subtends from x, or 2 (the whole sphere of directions)
 * from within it; by sin²θmax / (1 + cos θmax), exact for far, small spheres. */
inline float sphere_cone_1mcos(const KSphereLight* l, float3 x) {
  float3 d = (float3)(l->centre[0], l->centre[1], l->centre[2]) - x;
  float d2 = dot(d, d), r2 = l->radius * l->radius;
  if (!(d2 > r2)) return 2.0f;
  float sin2 = r2 / d2;
  return sin2 / (1.0f + sqrt(1.0f - sin2));
}

/* The solid-angle density of a front-facing point of the sphere light seen from x, picked with
 * probability `pick`. */
inline float sphere_light_pdf(const KSphereLight* l, float pick, float3 x) {
  return pick / (2.0f * KASHA_PI * sphere_cone_1mcos(l, x));
}

/* A direction uniform in the cone about `axis` whose 1 − cos θmax is `omc` (2: the whole sphere):
 * 1 − cos θ = u.x·omc and sin θ from it directly, so tiny cones keep their precision. */
inline float3 sample_cone_1mcos(float3 axis, float omc, float2 u) {
  float one_minus = u.x * omc, cos_t = 1.0f - one_minus;
  float sin_t = sqrt(fmax(0.0f, one_minus * (2.0f - one_minus)));
  float c, sn = sincos(2.0f * KASHA_PI * u.y, &c);
  float3 a, b;
  basis_around(axis, &a, &b);
  return normalize(sin_t * c * a + sin_t * sn * b + cos_t * axis);
}

/* A light point on sphere light l (picked with probability `pick`) for next-event estimation at
 * x, and its solid-angle density: 0 where the direction drawn meets something else first
 * (occluded, or missing the mesh) or a back side. The ray starts just short of the circumscribed
 * sphere: whatever lies before that is the shadow ray's to find. */
inline LightPoint sample_sphere_light(const SceneView* s, const KSphereLight* l, float pick, float3 x,
                                      float2 u, float* pdf) {
  float3 c = (float3)(l->centre[0], l->centre[1], l->centre[2]), to = c - x;
  float d2 = dot(to, to), r2 = l->radius * l->radius;
  float omc = sphere_cone_1mcos(l, x);
  float3 w = sample_cone_1mcos(d2 > 0.0f ? to * rsqrt(d2) : (float3)(0.0f, 0.0f, 1.0f), omc, u);
  float along = dot(to, w), tmin = 0.0f;
  if (d2 > r2) tmin = 0.999f * (along - sqrt(fmax(0.0f, r2 - (d2 - along * along))));
  LightPoint p = light_point(x, w, -1);
  *pdf = 0.0f;
  float t, bu, bv;
  ++s->rays->closest;
  AlphaTables alpha = scene_alpha(s);
  BvhTables bvh = scene_bvh(s);
  int inst; /* an emitter is among the scene's own triangles: instance 0's identity, if any */
  int hit = bvh_closest(&bvh, &alpha, x, w, fmax(tmin, 0.0f), INFINITY, &t, &bu, &bv, &inst);
  if (hit < 0 || s->tris[hit].emitter < 0) return p;
  int k = emitting_index(s, hit);
  if (k < 0 || !on_sphere_light(s, k, l)) return p;
  const __global KTriangle* tri = &s->tris[hit];
  float3 v0 = load_float3(tri->v0), v1 = load_float3(tri->v1), v2 = load_float3(tri->v2);
  p.normal = normalize(cross(v1 - v0, v2 - v0));
  if (dot(p.normal, w) >= 0.0f) return p; /* its back side: the sphere emits outward */
  /* From the barycentrics, as intersect_scene places a hit. */
  p.position = (1.0f - bu - bv) * v0 + bu * v1 + bv * v2;
  p.eps = surface_offset(v0, v1, v2, 1.0f - bu - bv, bu, bv, p.normal);
  p.emitter = tri->emitter;
#if KASHA_EMISSION_TEXTURES
  p.scale = emission_factor(s, hit, bu, bv);
#endif
  *pdf = sphere_light_pdf(l, pick, x);
  return p;
}

#endif /* KASHA_SPHERE_LIGHTS */

#endif
