/* The closest hit along a ray, with what every integrator asks of it: the point, the geometric
 * normal, the normal on the side the ray came from, and the triangle's material and emitter. */
#ifndef KASHA_HIT_POINT_H
#define KASHA_HIT_POINT_H

#include "geometry/bvh_traversal.h"
#include "geometry/scene_view.h"

#ifndef KASHA_TEXTURES
#define KASHA_TEXTURES 0
#endif
#ifndef KASHA_COATED
#define KASHA_COATED 0
#endif
#ifndef KASHA_SHADING_NORMALS
#define KASHA_SHADING_NORMALS 0
#endif
/* Shading normals from the vertices' normals (KShadingNormals); without them a normal map's
 * shading normal starts from the geometric one. */
#ifndef KASHA_VERTEX_NORMALS
#define KASHA_VERTEX_NORMALS KASHA_SHADING_NORMALS
#endif
#ifndef KASHA_ANISOTROPIC
#define KASHA_ANISOTROPIC 0
#endif
#ifndef KASHA_NORMAL_MAPS
#define KASHA_NORMAL_MAPS 0 /* some shape's material has a normal map */
#endif
#ifndef KASHA_MIX
#define KASHA_MIX 0 /* some shape's material is a mix */
#endif

/* With shading normals (KASHA_SHADING_NORMALS, docs/formats.md#shading-normals), ns is the
 * interpolated shading normal, or the material's normal map's (materials/hit_material.h), turned to
 * the geometric front's hemisphere, then to the ray's side,
 * and ng the geometric one on the ray's side: surfaces scatter about ns, while offsets, the side a
 * new ray leaves by and the check against light leaks use ng. Without them ns is the geometric
 * normal and hit_ng returns it. */
typedef struct {
  float3 x;      /* the hit point */
  float3 n;      /* geometric normal, (v1 − v0) × (v2 − v0) normalized: the front side */
  float3 ns;     /* the (shading) normal on the side the ray arrived from */
#if KASHA_SHADING_NORMALS
  float3 ng;     /* the geometric normal on the side the ray arrived from */
  float3 nf;     /* the shading normal on the front side */
#endif
  bool front;    /* the ray arrived on the front side */
  float t;       /* distance along the (unit) direction */
  float eps;     /* how far off the surface new rays start: x's own rounding bound (surface_offset) */
  int material;  /* the triangle's; a mix's choice once materials/hit_material.h resolves it */
  int emitter;   /* -1: the triangle does not emit */
  int tri;       /* the triangle, in leaf order */
#if KASHA_INSTANCES
  int instance;  /* the instance it was met in (its vertices are the object's) */
#endif
#if KASHA_TEXTURES || KASHA_MIX || KASHA_NORMAL_MAPS
  float2 b;      /* the barycentrics of v1 and v2: texture coordinates, a mix's amount, a normal map */
#endif
#if KASHA_COATED
  float cos_in;  /* |cos| of the arriving ray to the normal: a coat's Fresnel reflectance there */
#endif
} HitPoint;

#if KASHA_ANISOTROPIC || KASHA_NORMAL_MAPS
/* ∂p/∂u at the hit, in world space (a direction: the instance's linear part carries it). */
inline float3 hit_dpdu(const SceneView* s, const HitPoint* h) {
  float3 d = load_float3(s->tangents[h->tri].dpdu);
#if KASHA_INSTANCES
  d = affine_direction(s->instances[h->instance].world_from_object, d);
#endif
  return d;
}
#endif

/* γ(n) = n·u / (1 − n·u), u = 2^-24: the relative bound on n float roundings (pbrt-v4). */
#define KASHA_GAMMA(n) ((n) * 5.9604645e-8f / (1.0f - (n) * 5.9604645e-8f))

/* How far along the normal n a point b0·v0 + b1·v1 + b2·v2 of a triangle must be moved so that
 * rays leaving it miss the triangle: the interpolation's rounding bound γ(7)·Σ|b_k v_k| projected
 * on n (pbrt-v4's offset), plus the intersection test's own rounding, which grows with the
 * triangle's edges; doubled for margin. It depends on where the scene sits only as float
 * resolution does. */
inline float surface_offset(float3 v0, float3 v1, float3 v2, float b0, float b1, float b2, float3 n) {
  float3 err = fabs(b0 * v0) + fabs(b1 * v1) + fabs(b2 * v2);
  return 2.0f * KASHA_GAMMA(7) * (dot(fabs(n), err) + length(v1 - v0) + length(v2 - v0));
}

/* The closest hit's geometry within tmax, its material the triangle's: integrators meet surfaces
 * through materials/hit_material.h's intersect_surface, which resolves a mix and a normal map
 * there. Not counted (intersect_scene counts a ray; media/medium.h counts its shadow rays). */
inline bool intersect_scene_within(const SceneView* s, float3 org, float3 dir, float tmax, HitPoint* h) {
  float t, u, v;
  AlphaTables alpha = scene_alpha(s);
  BvhTables bvh = scene_bvh(s);
  int inst;
  int hit = bvh_closest(&bvh, &alpha, org, dir, 0.0f, tmax, &t, &u, &v, &inst);
  if (hit < 0) return false;
  const __global KTriangle* tri = &s->tris[hit];
  float3 v0 = load_float3(tri->v0), v1 = load_float3(tri->v1), v2 = load_float3(tri->v2);
#if KASHA_INSTANCES
  /* Everything downstream is in world space: the object's triangle placed. */
  const __global KInstance* in = &s->instances[inst];
  v0 = affine_point(in->world_from_object, v0);
  v1 = affine_point(in->world_from_object, v1);
  v2 = affine_point(in->world_from_object, v2);
  h->instance = inst;
#endif
  h->n = normalize(cross(v1 - v0, v2 - v0));
#if KASHA_INSTANCES
  if (in->mirrors) h->n = -h->n;
#endif
  h->front = dot(h->n, dir) < 0.0f;
  h->ns = h->front ? h->n : -h->n;
#if KASHA_SHADING_NORMALS
  {
#if KASHA_VERTEX_NORMALS
    const __global float* sn = s->normals[hit].n;
    float3 n = (1.0f - u - v) * (float3)(sn[0], sn[1], sn[2]) + u * (float3)(sn[3], sn[4], sn[5]) +
               v * (float3)(sn[6], sn[7], sn[8]);
#if KASHA_INSTANCES
    n = affine_normal(in->object_from_world, n);
#endif
    float len = length(n);
    /* A degenerate interpolation shades flat; a normal against the winding is turned to the front. */
    n = len > 1e-6f ? n / len : h->n;
    if (dot(n, h->n) < 0.0f) n = -n;
#else
    float3 n = h->n;
#endif
    h->nf = n;
    h->ng = h->ns;
    h->ns = h->front ? n : -n;
  }
#endif
  /* From the barycentrics, so its error depends on the triangle, not on the ray's length. */
  h->x = (1.0f - u - v) * v0 + u * v1 + v * v2;
  h->eps = surface_offset(v0, v1, v2, 1.0f - u - v, u, v, h->n);
  h->t = t;
  h->material = tri->material;
  h->emitter = tri->emitter;
  h->tri = hit;
#if KASHA_TEXTURES || KASHA_MIX || KASHA_NORMAL_MAPS
  h->b = (float2)(u, v);
#endif
  return true;
}

/* The closest hit along the whole ray, counted as a traced ray. */
inline bool intersect_scene(const SceneView* s, float3 org, float3 dir, HitPoint* h) {
  ++s->rays->closest;
  return intersect_scene_within(s, org, dir, INFINITY, h);
}

/* The geometric normal on the side the ray arrived from (ns itself without shading normals). */
inline float3 hit_ng(const HitPoint* h) {
#if KASHA_SHADING_NORMALS
  return h->ng;
#else
  return h->ns;
#endif
}

/* The (shading) normal on the front side. */
inline float3 hit_front(const HitPoint* h) {
#if KASHA_SHADING_NORMALS
  return h->nf;
#else
  return h->n;
#endif
}

/* Whether a direction d leaving the hit lies on the side of the geometric surface that the
 * shading normal assigns it (a reflection above, a refraction below): otherwise light would leak
 * through the surface, and the path ends. Always true without shading normals. */
inline bool hit_no_leak(const HitPoint* h, float3 d) {
#if KASHA_SHADING_NORMALS
  return (dot(d, h->ns) > 0.0f) == (dot(d, h->ng) > 0.0f);
#else
  return true;
#endif
}

/* Whether a ray arriving along d meets the surface from above its shading normal's hemisphere.
 * A surface scatters only between directions on that side (as pbrt-v4's BxDFs in the shading
 * frame), so light arriving, or a viewer looking, from below it (at silhouettes of smooth-shaded
 * meshes) sees nothing scattered; both directions of transport agree on it. */
inline bool hit_seen(const HitPoint* h, float3 d) {
#if KASHA_SHADING_NORMALS
  return dot(d, h->ns) < 0.0f;
#else
  return true;
#endif
}

/* Whether anything blocks the segment from x (offset eps off its surface along ns) to dist along
 * wi, short of the far end's own offset far_eps (measured along wi: a surface met at a grazing
 * angle needs its offset over the cosine) and of the rounding of dist itself. */
inline bool segment_occluded(const SceneView* s, float3 x, float3 ns, float eps, float3 wi, float dist, float far_eps) {
  /* 10⁻⁴ of the distance short, as pbrt-v4's ShadowEpsilon: a light point found along a ray or
   * interpolated on a triangle met at a grazing angle is only that good along the ray. */
  float reach = dist * (1.0f - 1e-4f) - eps - far_eps;
  if (!(reach > 0.0f)) return false;
  ++s->rays->shadow;
  AlphaTables alpha = scene_alpha(s);
  BvhTables bvh = scene_bvh(s);
  return bvh_occluded(&bvh, &alpha, x + ns * eps, wi, 0.0f, reach);
}

/* n more into a 64-bit count kept as (low, high) 32-bit words: 32-bit atomics are everywhere, and
 * the add that wraps the low word carries one into the high word, so the sum stays exact. */
inline void add_count(volatile __global uint* lo_hi, uint n) {
  if (n == 0u) return;
  uint before = atomic_add(lo_hi, n);
  if (before + n < before) atomic_inc(lo_hi + 1);
}

/* At the end of a work item: its rays into the job's counters (KASHA_FILM_PARAMS' ray_counts). */
inline void add_ray_counts(const SceneView* s, __global uint* counts) {
  add_count(counts, s->rays->closest);
  add_count(counts + 2, s->rays->shadow);
}

#endif
