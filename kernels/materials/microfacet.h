/* The GGX (Trowbridge–Reitz) microfacet distribution with anisotropic roughness (alpha_x,
 * alpha_y), as pbrt-v4 writes it, in a local frame whose z is the surface normal: the normal
 * distribution D, Smith's masking Lambda, G1 and G, and sampling of the normals visible from a
 * direction (Heitz 2018) with their density D_w (docs/materials.md#rough-surfaces). */
#ifndef KASHA_MICROFACET_H
#define KASHA_MICROFACET_H

#include "sampling/sampling.h"

/* pbrt-v4's threshold below which a distribution is treated as a perfectly smooth one. */
#define KASHA_SMOOTH_ALPHA 1e-3f

typedef struct {
  float ax, ay;
} Ggx;

/* The local frame of a surface: x, y tangents, z the front normal. An isotropic distribution
 * needs no particular x (frame_of picks one); an anisotropic one's x is the surface's ∂p/∂u
 * (surface.h: surface_frame). */
typedef struct {
  float3 s, t, n;
} Frame;

inline Frame frame_of(float3 n) {
  Frame f;
  f.n = n;
  basis_around(n, &f.s, &f.t);
  return f;
}
inline float3 to_local(const Frame* f, float3 v) { return (float3)(dot(v, f->s), dot(v, f->t), dot(v, f->n)); }
inline float3 to_world(const Frame* f, float3 v) { return v.x * f->s + v.y * f->t + v.z * f->n; }


inline float ggx_tan2(float3 w) {
  float c2 = w.z * w.z;
  return fmax(0.0f, 1.0f - c2) / c2;
}

/* cos² φ and sin² φ of w's azimuth (1, 0 at the pole). */
inline float2 ggx_cos_sin2_phi(float3 w) {
  float s2 = w.x * w.x + w.y * w.y;
  if (s2 <= 0.0f) return (float2)(1.0f, 0.0f);
  return (float2)(w.x * w.x / s2, w.y * w.y / s2);
}

inline float ggx_d(Ggx a, float3 wm) {
  float t2 = ggx_tan2(wm);
  if (isinf(t2)) return 0.0f;
  float c4 = wm.z * wm.z * wm.z * wm.z;
  float2 cs = ggx_cos_sin2_phi(wm);
  float e = t2 * (cs.x / (a.ax * a.ax) + cs.y / (a.ay * a.ay));
  return 1.0f / (KASHA_PI * a.ax * a.ay * c4 * (1.0f + e) * (1.0f + e));
}

inline float ggx_lambda(Ggx a, float3 w) {
  float t2 = ggx_tan2(w);
  if (isinf(t2)) return 0.0f;
  float2 cs = ggx_cos_sin2_phi(w);
  float alpha2 = cs.x * a.ax * a.ax + cs.y * a.ay * a.ay;
  return (sqrt(1.0f + alpha2 * t2) - 1.0f) * 0.5f;
}

inline float ggx_g1(Ggx a, float3 w) { return 1.0f / (1.0f + ggx_lambda(a, w)); }
inline float ggx_g(Ggx a, float3 wo, float3 wi) { return 1.0f / (1.0f + ggx_lambda(a, wo) + ggx_lambda(a, wi)); }

/* The density of the normals visible from w: G1(w) / |cos θ_w| · D(wm) · |w·wm|. */
inline float ggx_visible_pdf(Ggx a, float3 w, float3 wm) {
  return ggx_g1(a, w) / fabs(w.z) * ggx_d(a, wm) * fabs(dot(w, wm));
}

/* A normal drawn from the visible normals of w (w on either side: the distribution is that of
 * the side w is on, mirrored), u uniform in [0, 1)². */
inline float3 ggx_sample_visible(Ggx a, float3 w, float2 u) {
  float3 wh = normalize((float3)(a.ax * w.x, a.ay * w.y, w.z));
  if (wh.z < 0.0f) wh = -wh;
  float3 t1 = wh.z < 0.99999f ? normalize(cross((float3)(0.0f, 0.0f, 1.0f), wh)) : (float3)(1.0f, 0.0f, 0.0f);
  float3 t2 = cross(wh, t1);
  /* A uniform point of the unit disk (polar), warped to the projected visible hemisphere. */
  float r = sqrt(u.x), phi = 2.0f * KASHA_PI * u.y;
  float px = r * cos(phi), py = r * sin(phi);
  float h = sqrt(fmax(0.0f, 1.0f - px * px));
  py = mix(h, py, (1.0f + wh.z) * 0.5f);
  float pz = sqrt(fmax(0.0f, 1.0f - px * px - py * py));
  float3 nh = px * t1 + py * t2 + pz * wh;
  return normalize((float3)(a.ax * nh.x, a.ay * nh.y, fmax(1e-6f, nh.z)));
}

#endif
