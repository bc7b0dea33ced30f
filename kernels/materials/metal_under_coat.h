/* The metal part of a rough layered metal (pbrt-v4's coatedconductor with a rough interface or a
 * rough conductor; docs/materials.md#rough-coated-conductors): the conductor's GGX lobe seen
 * through the coat, light scattered once by the metal. Directions cross the coat by smooth
 * refraction (a rough coat's spread is in the metal's alpha, host/material/layered_metal.h), so
 * with wo', wi' the directions inside and t(μ) the coat's transmission (coat.h),
 *     f(wo, wi) = t(μo) t(μi) / η² · D(wm) G(wo', wi') / (4 μo' μi') · Fc(|wo'·wm|),
 * reciprocal; Fc (the metal's index over the coat's) is left to the caller (coated_conductor.h),
 * as for a bare rough conductor. Light the metal sends beyond the coat's escape cone, and every
 * later round trip, is the layer's other part (a coated Lambert part of the same material). */
#ifndef KASHA_METAL_UNDER_COAT_H
#define KASHA_METAL_UNDER_COAT_H

#include "materials/coat.h"
#include "materials/rough_interface.h"

#if KASHA_ROUGH
#if KASHA_COATED && KASHA_CONDUCTOR
/* w (pointing away from the surface, z > 0) refracted into the coat of index eta. */
inline float3 coat_inside(float3 w, float eta) {
  float3 v = (float3)(w.x / eta, w.y / eta, 0.0f);
  v.z = sqrt(fmax(0.0f, 1.0f - v.x * v.x - v.y * v.y));
  return v;
}

/* The density of wi (outside, cosine mu_i; mu_i' inside) from the visible normal wm of o: the
 * reflection's density inside times the refraction's Jacobian μi / (η² μi'). */
inline float metal_under_coat_pdf(Ggx a, float3 o, float3 wm, float cos_m, float mu_i, float mu_i_in, float eta) {
  return ggx_visible_pdf(a, o, wm) / (4.0f * cos_m) * mu_i / (eta * eta * mu_i_in);
}

/* f(wo, wi) without Fc; *pdf the density of metal_under_coat_sample; *cos_m Fc's cosine. */
inline float metal_under_coat_eval(const Surface* s, float3 wo, float3 wi, float* pdf, float* cos_m) {
  *pdf = 0.0f;
  if (wo.z * wi.z <= 0.0f) return 0.0f;
  if (wo.z < 0.0f) { /* two-sided, as pbrt-v4's layered BxDFs */
    wo.z = -wo.z;
    wi.z = -wi.z;
  }
  float eta = s->coat_c.x;
  float3 o = coat_inside(wo, eta), i = coat_inside(wi, eta);
  if (!(o.z > 0.0f && i.z > 0.0f)) return 0.0f;
  float3 wm = normalize(o + i);
  *cos_m = dot(o, wm);
  *pdf = metal_under_coat_pdf(s->alpha, o, wm, *cos_m, wi.z, i.z, eta);
  float t = coat_transmission(s, wo.z) * coat_transmission(s, wi.z);
  return t / (eta * eta) * ggx_d(s->alpha, wm) * ggx_g(s->alpha, o, i) / (4.0f * o.z * i.z);
}

/* wi from wo: into the coat, a visible normal of the metal, out again (lost where the
 * reflection lies beyond the coat's escape cone). weight: f cos θi / pdf = t(μo) t(μi) G / G1. */
inline bool metal_under_coat_sample(const Surface* s, float3 wo, float2 u, InterfaceSample* smp) {
  if (wo.z == 0.0f) return false;
  float side = wo.z > 0.0f ? 1.0f : -1.0f;
  wo.z *= side;
  float eta = s->coat_c.x;
  float3 o = coat_inside(wo, eta);
  if (!(o.z > 0.0f)) return false;
  float3 wm = ggx_sample_visible(s->alpha, o, u);
  float3 i = reflect_about(o, wm);
  if (i.z <= 0.0f) return false;
  float3 wi = (float3)(i.x * eta, i.y * eta, 0.0f);
  float sin2 = wi.x * wi.x + wi.y * wi.y;
  if (sin2 >= 1.0f) return false;
  wi.z = sqrt(1.0f - sin2);
  smp->cos_m = fabs(dot(o, wm));
  smp->pdf = metal_under_coat_pdf(s->alpha, o, wm, smp->cos_m, wi.z, i.z, eta);
  smp->weight = coat_transmission(s, wo.z) * coat_transmission(s, wi.z) * ggx_g(s->alpha, o, i) / ggx_g1(s->alpha, o);
  smp->transmitted = false;
  wi.z *= side;
  smp->wi = wi;
  return true;
}
#endif

/* A rough conductor's lobe, bare or under a rough layer's coat: f without Fc (rough_interface.h). */
inline float conductor_lobe_eval(const Surface* s, float3 wo, float3 wi, float* pdf, float* cos_m) {
#if KASHA_COATED && KASHA_CONDUCTOR
  if (s->coat_c.z > 0.0f) return metal_under_coat_eval(s, wo, wi, pdf, cos_m);
#endif
  return rough_conductor_eval(wo, wi, s->alpha, pdf, cos_m);
}

inline bool conductor_lobe_sample(const Surface* s, float3 wo, float2 u, InterfaceSample* smp) {
#if KASHA_COATED && KASHA_CONDUCTOR
  if (s->coat_c.z > 0.0f) return metal_under_coat_sample(s, wo, u, smp);
#endif
  return rough_conductor_sample(wo, s->alpha, u, smp);
}
#endif

#endif
