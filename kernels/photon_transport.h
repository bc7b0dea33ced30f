/* Photons from the lights (DESIGN §2.1): emission, and the one routine that decides what happens
 * at a hit — constant-energy branching by the branch energies under the photon's spectrum. The
 * caller decides what to do at the hit (splat to the camera, or store in the photon map).
 * A photon's spectrum is its power per bin (W). */
#ifndef KASHA_PHOTON_TRANSPORT_H
#define KASHA_PHOTON_TRANSPORT_H

#include "gloss_lobe.h"
#include "lights.h"
#include "rng.h"
#include "sampling.h"
#include "scene_view.h"
#include "spectral_product.h"
#include "surface.h"

typedef struct {
  float3 position;
  float3 direction;
  float power[KASHA_BINS];
} Photon;

enum { BRANCH_ABSORBED = 0, BRANCH_GLOSS = 1, BRANCH_PASSIVE = 2, BRANCH_FLUORESCENT = 3 };

/* Where a photon left its light: the light's normal, its emitter, and the area density p_area
 * with which the point was chosen. */
typedef struct {
  float3 normal;
  int emitter;
  float area_pdf;
} LightOrigin;

/* A photon leaving a light: a triangle chosen by power, a uniform point, a cosine-weighted
 * direction; its spectrum is the emitter's radiance scaled so that the `photons` of a pass carry
 * the lights' total power: Φ_i = Le_i Δλ · π / (p_area · photons). */
inline Photon emit_photon(const SceneView* s, float photons, Rng* rng, LightOrigin* origin) {
  float3 u = rng_next_float3(rng);
  LightPoint lp = sample_light(s->tris, s->light_tri, s->light_cdf, s->light_count, u.x, u.y, u.z);
  Photon p;
  p.position = lp.position;
  float2 d = rng_next_float2(rng);
  p.direction = sample_cosine_hemisphere(lp.normal, d.x, d.y);
  origin->normal = lp.normal;
  origin->emitter = lp.emitter;
  origin->area_pdf = s->emitter_area_pdf[lp.emitter];
  float scale = s->bin_nm * KASHA_PI / (origin->area_pdf * photons);
  const __global float* le = emitter_spectrum(s, lp.emitter);
  for (int i = 0; i < KASHA_BINS; ++i) p.power[i] = le[i] * scale;
  return p;
}

inline float photon_total(const Photon* p) {
  float s = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) s += p->power[i];
  return s;
}

/* Scatters the photon at x (ns: the normal on the side it arrived from). Chooses gloss, passive
 * or fluorescent re-emission with probability P_k / ΣΦ, P_g = g ΣΦ, P_p = Σ ρ_i Φ_i,
 * P_f = Σ a_i Φ_i, or absorption; the new spectrum (g Φ, ρ∘Φ or ê (a·Φ)) is rescaled by ΣΦ/P_k so
 * the photon keeps its power (the cone lobe's cosine ratio aside). Returns the branch. */
inline int scatter_photon(Photon* p, const Surface* s, const SceneView* scene, float3 x, float3 ns, Rng* rng) {
  const float ray_eps = scene->ray_eps;
  float total = photon_total(p);
  float pg = s->g * total, pp = 0.0f, pf = 0.0f;
  if (s->passive) pp = spectrum_dot(KASHA_BINS, p->power, s->rho, 0);
#if KASHA_FLUORESCENCE
  if (s->fluorescent) pf = spectrum_dot(KASHA_BINS, p->power, s->a, 0);
#endif
  float xi = rng_next_float(rng) * total;
  float u1 = rng_next_float(rng), u2 = rng_next_float(rng);
  float3 d_in = p->direction;
  if (xi < pg) {
    float3 mirror = reflect_dir(d_in, ns);
    if (s->mirror) {
      p->direction = mirror;
    } else {
      float pdf;
      float3 wo = sample_lobe(s->m, scene->lobes, mirror, u1, u2, rng_next_float(rng), &pdf);
      float co = dot(wo, ns), ci = -dot(d_in, ns);
      if (co <= 0.0f) return BRANCH_ABSORBED;
      float k = 2.0f * co / (ci + co);
      for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= k;
      p->direction = wo;
    }
    p->position = x + ns * ray_eps;
    return BRANCH_GLOSS;
  }
  if (xi < pg + pp) {
    float k = total / pp;
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= s->rho[i] * k;
    p->direction = sample_cosine_hemisphere(ns, u1, u2);
    p->position = x + ns * ray_eps;
    return BRANCH_PASSIVE;
  }
#if KASHA_FLUORESCENCE
  if (xi < pg + pp + pf) {
    /* The photon changes colour: all its power re-emitted with the emission spectrum. */
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] = s->ehat[i] * total;
    p->direction = sample_cosine_hemisphere(ns, u1, u2);
    p->position = x + ns * ray_eps;
    return BRANCH_FLUORESCENT;
  }
#endif
  return BRANCH_ABSORBED;
}

#endif
