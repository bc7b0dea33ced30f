/* Next-event estimation: the emitting triangles together keep their share of the lights' power
 * (a CDF over the emitting triangles and the other lights, what photons leave by), and within it
 * the light BVH (light_bvh.h) picks one given the shading point; then a point on it: uniform in
 * the solid angle it subtends from the shading point (Arvo 1995, as pbrt-v4 does) when that angle
 * lies between KASHA_MIN_SPHERICAL_SOLID_ANGLE and KASHA_MAX_SPHERICAL_SOLID_ANGLE, uniform in
 * area otherwise; an emitting sphere is one light, sampled by the solid angle it subtends
 * (sphere_light.h). Light paths choose a triangle by power alone: since a triangle's power is its
 * area times pi times its emitter's band-integrated radiance, the area density of their start,
 * p(triangle)/area, depends only on the emitter: emitter_area_pdf[e]. */
#ifndef KASHA_LIGHTS_H
#define KASHA_LIGHTS_H

#include "geometry/bvh_traversal.h"
#include "lights/environment.h"
#include "lights/light_bvh.h"
#include "lights/light_point.h"
#include "lights/sphere_light.h"
#include "geometry/hit_point.h"
#include "sampling/sampling.h"
#include "geometry/scene_view.h"
#include "materials/texture.h"

#ifndef KASHA_SPOT_LIGHTS
#define KASHA_SPOT_LIGHTS 0
#endif
#ifndef KASHA_INFINITE_LIGHTS
#define KASHA_INFINITE_LIGHTS 0
#endif

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

/* A uniform point on emitting triangle `tri`. */
inline LightPoint sample_light_on(const __global KTriangle* tris, int tri, float u1, float u2) {
  const __global KTriangle* t = &tris[tri];
  float3 v0 = load_float3(t->v0), e1 = load_float3(t->v1) - v0, e2 = load_float3(t->v2) - v0;
  float2 b = sample_triangle(u1, u2);
  LightPoint p;
  p.position = v0 + b.x * e1 + b.y * e2;
  p.normal = normalize(cross(e1, e2));
  p.emitter = t->emitter;
  p.eps = surface_offset(v0, v0 + e1, v0 + e2, 1.0f - b.x - b.y, b.x, b.y, p.normal);
#if KASHA_ENVIRONMENT
  p.le = 0;
#endif
  return p;
}

/* An emitting triangle chosen by power (u0), then a uniform point on it. */
inline LightPoint sample_light(const __global KTriangle* tris, const __global int* light_tri,
                               const __global float* light_cdf, int light_count, float u0, float u1, float u2) {
  return sample_light_on(tris, light_tri[choose_light(light_cdf, light_count, u0)], u1, u2);
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

#if KASHA_LIGHT_SOURCES

#if KASHA_SPOT_LIGHTS
/* A spot's intensity over its full intensity at the angle θ off its axis: pbrt-v4's smoothstep
 * from the cone's edge (0) to where the falloff begins (1). */
inline float spot_falloff(const __global KLight* l, float cos_theta) {
  if (cos_theta >= l->cos_falloff) return 1.0f;
  if (cos_theta <= l->cos_total) return 0.0f;
  float t = (cos_theta - l->cos_total) / (l->cos_falloff - l->cos_total);
  return t * t * (3.0f - 2.0f * t);
}

/* A direction uniform in the spot's cone (what its photons leave along); density
 * 1/(2π(1 − cos_total)). */
inline float3 sample_spot_cone(const __global KLight* l, float2 u) {
  float cos_t = 1.0f - u.x * (1.0f - l->cos_total), sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
  float c, sn = sincos(2.0f * KASHA_PI * u.y, &c);
  float3 axis = load_float3(l->axis), a, b;
  basis_around(axis, &a, &b);
  return normalize(sin_t * c * a + sin_t * sn * b + cos_t * axis);
}
#endif

#if KASHA_INFINITE_LIGHTS
/* The solid-angle density with which sample_light_source picks the direction w of the infinite
 * light l (its pick probability included), for MIS where a path escapes. */
inline float infinite_light_pdf(const SceneView* s, const __global KLight* l, float3 w) {
#if KASHA_ENVIRONMENT
  if (l->image >= 0) return l->pick * env_pdf(s, l, w);
#endif
  return l->pick * KASHA_INV_4PI;
}

/* The radiance an infinite light sends along -w (arriving from w). */
inline const __global float* infinite_light_spectrum(const SceneView* s, const __global KLight* l, float3 w) {
#if KASHA_ENVIRONMENT
  if (l->image >= 0) {
    float jacobian;
    return env_spectrum(s, l, env_texel(l, env_uv(l, w, &jacobian)), s->scratch);
  }
#endif
  return emitter_spectrum(s, l->spectrum);
}
#endif

/* A light that is not a triangle, seen from x: the direction to it as a point far along it for a
 * distant or infinite light (past the scene's bounding sphere, so the shadow ray sees everything
 * in between), its spectrum's row and the factor on it, and the density: the pick probability of
 * a delta light (point, spot, distant), times the direction's solid-angle density for an
 * infinite one. */
inline LightPoint sample_light_source(const SceneView* s, const __global KLight* l, float3 x, float2 u, float* pdf) {
  LightPoint p;
  p.emitter = l->spectrum;
  p.eps = 0.0f;
  p.scale = 1.0f;
  p.delta = true;
  p.source = l;
#if KASHA_ENVIRONMENT
  p.le = 0;
#endif
  *pdf = l->pick;
  float3 wi;
  if (l->type == KASHA_LIGHT_POINT || l->type == KASHA_LIGHT_SPOT) {
    p.position = load_float3(l->position);
    float3 to = p.position - x;
    float d2 = dot(to, to);
    wi = to / sqrt(d2);
    p.scale = 1.0f / d2;
#if KASHA_SPOT_LIGHTS
    if (l->type == KASHA_LIGHT_SPOT) p.scale *= spot_falloff(l, -dot(wi, load_float3(l->axis)));
#endif
  } else {
    if (l->type == KASHA_LIGHT_DISTANT) {
      wi = -load_float3(l->axis);
    } else {
      p.delta = false;
#if KASHA_ENVIRONMENT
      if (l->image >= 0) {
        int texel;
        float pdf_dir;
        wi = env_sample(s, l, u, &texel, &pdf_dir);
        *pdf = l->pick * pdf_dir;
        p.le = env_spectrum(s, l, texel, s->scratch);
      } else
#endif
      {
        wi = sample_uniform_sphere(u);
        *pdf = l->pick * KASHA_INV_4PI;
      }
    }
    p.position = x + wi * (2.0f * l->radius + length(x - load_float3(l->position)));
  }
  p.normal = -wi;
  if (!(p.scale > 0.0f) || !isfinite(p.scale)) *pdf = 0.0f;
  return p;
}

/* A photon's start at the light l (picked with probability l->pick): where and along what it
 * leaves, and what its spectrum is scaled by, per unit of the light's spectrum times the bin
 * width and over the pass's photons: 1/(pick · density), where the density is of the direction
 * (point, spot: Φ = I/p(ω)) or of the point on a disk as wide as the scene, facing the light's
 * direction (distant: Φ = E·πr²; infinite: Φ = L·πr²/p(ω)). u places the point, d the direction. */
inline float emit_from_source(const SceneView* s, const __global KLight* l, float2 u, float2 d, float3* position,
                              float3* direction, int* texel) {
  float3 centre = load_float3(l->position);
  *texel = -1;
  if (l->type == KASHA_LIGHT_POINT) {
    *position = centre;
    *direction = sample_uniform_sphere(d);
    return 4.0f * KASHA_PI / l->pick;
  }
#if KASHA_SPOT_LIGHTS
  if (l->type == KASHA_LIGHT_SPOT) {
    *position = centre;
    *direction = sample_spot_cone(l, d);
    float cone = 2.0f * KASHA_PI * (1.0f - l->cos_total);
    return spot_falloff(l, dot(*direction, load_float3(l->axis))) * cone / l->pick;
  }
#endif
  float3 w;
  float inv_pdf_dir = 4.0f * KASHA_PI;
  if (l->type == KASHA_LIGHT_DISTANT) {
    w = -load_float3(l->axis);
#if KASHA_ENVIRONMENT
  } else if (l->image >= 0) {
    float pdf_dir;
    w = env_sample(s, l, d, texel, &pdf_dir);
    inv_pdf_dir = pdf_dir > 0.0f ? 1.0f / pdf_dir : 0.0f;
#endif
  } else {
    w = sample_uniform_sphere(d);
  }
  float disk = KASHA_PI * l->radius * l->radius;
  float3 a, b;
  basis_around(w, &a, &b);
  float r = l->radius * sqrt(u.x), c, sn = sincos(2.0f * KASHA_PI * u.y, &c);
  *position = centre + l->radius * w + r * (c * a + sn * b);
  *direction = -w;
  return l->type == KASHA_LIGHT_DISTANT ? disk / l->pick : disk * inv_pdf_dir / l->pick;
}
#endif

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

/* A light point on emitting triangle `tri` (leaf order) for next-event estimation at x, which
 * picked the triangle with probability `pick`, and the solid-angle density of its direction (0
 * when the sample failed). */
inline LightPoint sample_light_triangle(const SceneView* s, int tri, float pick, float3 x, float2 u, float* pdf) {
  const __global KTriangle* t = &s->tris[tri];
  float3 v0 = load_float3(t->v0), v1 = load_float3(t->v1), v2 = load_float3(t->v2);
  float3 cr = cross(v1 - v0, v2 - v0);
  float area = 0.5f * length(cr);
  LightPoint p = light_point(x, normalize(cr), t->emitter); /* position and eps found below */
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
    if (dist > 0.0f && isfinite(dist)) *pdf = pick / omega;
  } else {
    float2 b = sample_triangle(u.x, u.y);
    p.position = v0 + b.x * (v1 - v0) + b.y * (v2 - v0);
    p.eps = surface_offset(v0, v1, v2, 1.0f - b.x - b.y, b.x, b.y, p.normal);
    float3 to = p.position - x;
    float d2 = dot(to, to), cos_l = -dot(p.normal, to) / sqrt(d2);
    if (cos_l > 0.0f) *pdf = pick / area * d2 / cos_l;
  }
#if KASHA_EMISSION_TEXTURES
  /* The point's barycentrics (the spherical branch found it along a ray), for its texture. */
  float3 e1 = v1 - v0, e2 = v2 - v0, q = p.position - v0;
  float inv = 1.0f / dot(cr, cr);
  p.scale = emission_factor(s, tri, dot(cross(q, e2), cr) * inv, dot(cross(e1, q), cr) * inv);
#endif
  return p;
}

/* The emitting triangles' share of light sampling (their power over all the lights'), as the CDF
 * the other lights are picked from has it. */
inline float light_triangle_share(const SceneView* s) { return s->light_cdf[s->light_triangles - 1]; }


/* A light point for next-event estimation at x, with the solid-angle density of having sampled
 * its direction (0 when the sample failed). u.x picks the light and, rescaled to the part of
 * [0, 1) that picked it, goes on with u.y to pick the point: the 2-D sample stays stratified over
 * all the emitting triangles together (a quad lamp's two triangles included). */
inline LightPoint sample_light_from(const SceneView* s, float3 x, float2 u, float* pdf) {
#if KASHA_LIGHT_SOURCES
  int lo = choose_light(s->light_cdf, s->light_count, u.x);
  if (s->light_tri[lo] < 0) {
    float below = lo > 0 ? s->light_cdf[lo - 1] : 0.0f, width = s->light_cdf[lo] - below;
    u.x = width > 0.0f ? clamp((u.x - below) / width, 0.0f, 0.99999994f) : 0.5f;
    return sample_light_source(s, &s->lights[~s->light_tri[lo]], x, u, pdf);
  }
#endif
  float share = light_triangle_share(s), pick, ux = clamp(u.x / share, 0.0f, 0.99999994f);
  int tri = light_bvh_sample(s->light_nodes, x, &ux, &pick);
  u.x = ux;
#if KASHA_SPHERE_LIGHTS
  /* A sphere is one leaf of the light BVH, its first triangle standing for it. */
  KSphereLight sphere = sphere_light_of(s, emitting_index(s, tri));
  if (sphere.radius > 0.0f) return sample_sphere_light(s, &sphere, share * pick, x, u, pdf);
#endif
  return sample_light_triangle(s, tri, share * pick, x, u, pdf);
}

/* The solid-angle density with which sample_light_from at x would pick the point y on leaf
 * triangle `tri` (front side seen, cos_light > 0), for multiple importance sampling. */
inline float light_pdf_from(const SceneView* s, int tri, float3 x, float3 y, float cos_light) {
  int j = emitting_index(s, tri);
  if (j < 0) return 0.0f;
  float pick = light_triangle_share(s) * light_bvh_pmf(s->light_nodes, s->light_trails[j], x);
#if KASHA_SPHERE_LIGHTS
  /* A sphere's triangles share its leaf's trail; its points are found by direction. */
  KSphereLight sphere = sphere_light_of(s, j);
  if (sphere.radius > 0.0f) return cos_light > 0.0f ? sphere_light_pdf(&sphere, pick, x) : 0.0f;
#endif
  const __global KTriangle* t = &s->tris[tri];
  float3 v0 = load_float3(t->v0), v1 = load_float3(t->v1), v2 = load_float3(t->v2);
  float omega = triangle_solid_angle(x, v0, v1, v2);
  if (spherical_sampling(omega)) return pick / omega;
  float3 to = y - x;
  return cos_light > 0.0f ? pick / (0.5f * length(cross(v1 - v0, v2 - v0))) * dot(to, to) / cos_light : 0.0f;
}

#endif
