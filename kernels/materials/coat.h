/* A smooth dielectric coat over a material's Lambert parts (docs/materials.md#coated-surfaces),
 * pbrt-v4's coateddiffuse with a smooth interface and an absorbing layer of optical depth d.
 * Under the coat the base is Lambertian, so every bounce between coat and base is diffuse, and
 * the series of them sums in closed form: with t(θ) = (1 − F(θ))·exp(−d / cos θt),
 *     f(wo, wi) = F(θo) δ(mirror)  +  t(θo) t(θi) / η² · (diag(ρ') + ê' a'ᵀ) / π,
 * where the base's bin matrix B = diag(ρ) + ê aᵀ becomes B (I − R̄ B)⁻¹ (R̄: the coat's internal
 * reflectance, host/material/coat.h), again diagonal plus rank 1 by Sherman–Morrison:
 *     ρ' = ρ / (1 − R̄ρ),   ê' = ê / (1 − R̄ρ) / s,   a' = s · a / (1 − R̄ρ) / (1 − R̄ Σ a ê / (1 − R̄ρ)),
 * with s = Σ ê / (1 − R̄ρ), so that ê' sums to 1 as every emission spectrum does.
 * The surface then looks like a measured one: its mirror lobe is the coat's F(θo), its Lambert
 * parts are ρ', ê', a' with the extra factors t(θo) t(θi) / η², so every integrator uses its
 * existing code with two scalars (coat_at; surface_lambert_weight).
 * Defines: KASHA_COATED, KASHA_SCRATCH_COAT (where the effective spectra go in the scratch). */
#ifndef KASHA_COAT_H
#define KASHA_COAT_H

#include "materials/fresnel.h"
#include "materials/rough_interface.h"
#include "geometry/scene_view.h"
#include "materials/surface.h"

#ifndef KASHA_SCRATCH_COAT
#define KASHA_SCRATCH_COAT 0
#endif

#if KASHA_COATED
/* A coat's table (E(μ) at 0, t(μ) at KASHA_COAT_TABLE) at μ, linear between its nodes. */
inline float coat_table_at(const Surface* s, int which, float mu) {
  float x = clamp(mu, 0.0f, 1.0f) * (float)(KASHA_COAT_TABLE - 1);
  int k = min((int)x, KASHA_COAT_TABLE - 2);
  const __global float* t = s->coat_table + which * KASHA_COAT_TABLE;
  return t[k] + (x - (float)k) * (t[k + 1] - t[k]);
}

inline bool coat_rough(const Surface* s) { return s->m->coat_alpha > 0.0f; }

/* t(θ) at cos θ on the outside: a rough coat's table, or a layered metal's Lambert part's own
 * (host/material/layered_metal.h), else the smooth coat's. */
inline float coat_transmission(const Surface* s, float cos_theta) {
  if (s->m->coat_table >= 0) return coat_table_at(s, 1, cos_theta);
  float eta = s->m->coat_eta;
  cos_theta = clamp(cos_theta, 0.0f, 1.0f);
  float sin2_t = (1.0f - cos_theta * cos_theta) / (eta * eta);
  if (sin2_t >= 1.0f) return 0.0f;
  float cos_t = sqrt(1.0f - sin2_t), d = s->m->coat_thickness;
  return (1.0f - fresnel_dielectric(cos_theta, eta)) * (d > 0.0f ? exp(-d / cos_t) : 1.0f);
}

/* A coated surface met from the direction at cos_o to the normal (the viewer's, or a photon's
 * arrival): the coat's reflectance becomes the mirror lobe, the Lambert parts' factors for that
 * side are set, and the effective spectra are computed into the scratch from the (possibly
 * textured) base's. */
inline void coat_at(const SceneView* sv, Surface* s, float cos_o) {
  const __global KMaterial* m = s->m;
  float R = m->coat_internal;
  /* A smooth coat's mirror reflection, or a rough one's GGX lobe (coat_lobe_*): its albedo. */
  s->mirror = !coat_rough(s);
  s->g = (s->mirror ? fresnel_dielectric(cos_o, m->coat_eta) : coat_table_at(s, 0, cos_o)) * m->layer_scale;
  float t = coat_transmission(s, cos_o);
  s->lambert_out = t / (m->coat_eta * m->coat_eta);
  s->lambert_albedo = t * m->coat_albedo;
  __global float* rho = sv->scratch + KASHA_SCRATCH_COAT;
  for (int i = 0; i < KASHA_BINS; ++i) rho[i] = s->passive ? s->rho[i] / (1.0f - R * s->rho[i]) : 0.0f;
#if KASHA_FLUORESCENCE
  if (s->fluorescent) {
    __global float* e = rho + KASHA_BINS;
    __global float* a = e + KASHA_BINS;
    /* 1/(1 − R̄ρ) is 1 + R̄ρ' : read back from ρ'. */
    float esum = 0.0f, ae = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) {
      float k = 1.0f + R * rho[i];
      e[i] = s->ehat[i] * k;
      esum += e[i];
      ae += s->a[i] * e[i];
    }
    float scale = esum / (1.0f - R * ae), a_sum = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) {
      e[i] /= esum;
      a[i] = s->a[i] * (1.0f + R * rho[i]) * scale;
      a_sum += a[i];
    }
    s->ehat = e;
    s->a = a;
    s->a_sum = a_sum;
  }
#endif
  if (s->passive) {
    /* A rough layered metal's scattered part is chosen at a share of points (layered_metal.h). */
    if (m->layer_scale != 1.0f)
      for (int i = 0; i < KASHA_BINS; ++i) rho[i] *= m->layer_scale;
    s->rho = rho;
  }
}

/* A rough coat's reflection lobe (pbrt-v4's rough DielectricBxDF, reflection only) in a local
 * frame about the normal on the viewer's side: f(wo, wi) and the density of sampling wi from wo. */
inline float coat_lobe_eval(const Surface* s, float3 wo, float3 wi, float* pdf) {
  Ggx a = {s->m->coat_alpha, s->m->coat_alpha};
  float cos_m;
  float f = rough_conductor_eval(wo, wi, a, pdf, &cos_m);
  return f > 0.0f ? f * fresnel_dielectric(cos_m, s->m->coat_eta) * s->m->layer_scale : 0.0f;
}

/* A direction from the lobe: a visible normal, the mirror direction about it; *weight is
 * f cos θi / pdf = F G / G1. False: it left below the surface. */
inline bool coat_lobe_sample(const Surface* s, float3 wo, float2 u, float3* wi, float* weight, float* pdf) {
  Ggx a = {s->m->coat_alpha, s->m->coat_alpha};
  InterfaceSample smp;
  if (!rough_conductor_sample(wo, a, u, &smp) || !(smp.pdf > 0.0f)) return false;
  *wi = smp.wi;
  *pdf = smp.pdf;
  *weight = smp.weight * fresnel_dielectric(smp.cos_m, s->m->coat_eta) * s->m->layer_scale;
  return true;
}

/* Whether the surface's gloss part is a rough coat's lobe (not the measured model's table). */
inline bool surface_coat_lobe(const Surface* s) { return s->coated && !s->mirror; }
#endif

/* The Lambert parts' factor for a bounce that leaves (or arrives) at cos_new on the far side of
 * the vertex from where it was met: t(θ) t(θnew) / η² on a coated surface, else 1. */
inline float surface_lambert_weight(const Surface* s, float cos_new) {
#if KASHA_COATED
  if (s->coated) return s->lambert_out * coat_transmission(s, cos_new);
#endif
  return 1.0f;
}

/* The Lambert parts' directional albedo per unit of their spectra, for the branch choice:
 * t(θ) τ̄ / η² on a coated surface, else 1. */
inline float surface_lambert_albedo(const Surface* s) {
#if KASHA_COATED
  if (s->coated) return s->lambert_albedo;
#endif
  return 1.0f;
}

#endif
