/* Rough dielectric and conductor interfaces: GGX microfacets (microfacet.h) with Fresnel
 * reflection and refraction at each facet, single scattering, as pbrt-v4's DielectricBxDF and
 * ConductorBxDF (docs/materials.md#rough-surfaces). Directions are local (z: the surface's front
 * normal) and point away from the surface: wo towards the viewer (the camera side of a camera
 * path, where a photon came from), wi towards the light. `radiance`: camera paths carry
 * radiance, whose transmission takes 1/etap²; photons carry flux, which does not. A conductor's
 * Fresnel factor F(λ, |wo·wm|) is left to the caller, which applies it bin by bin. */
#ifndef KASHA_ROUGH_INTERFACE_H
#define KASHA_ROUGH_INTERFACE_H

#include "materials/fresnel.h"
#include "materials/microfacet.h"

typedef struct {
  float3 wi;
  float pdf;    /* per solid angle, the reflection/refraction choice included */
  float weight; /* f |cos θi| / pdf (without a conductor's F) */
  float cos_m;  /* |wo·wm|: a conductor's Fresnel argument */
  bool transmitted;
} InterfaceSample;

/* Fresnel reflectance at a facet for the dielectric of relative index eta (back over front), with
 * cos_o = wo·wm signed: negative when wo lies behind the facet. */
inline float facet_fresnel(float cos_o, float eta) {
  return cos_o >= 0.0f ? fresnel_dielectric(cos_o, eta) : fresnel_dielectric(-cos_o, 1.0f / eta);
}

inline float3 reflect_about(float3 wo, float3 n) { return -wo + 2.0f * dot(wo, n) * n; }

/* A rough dielectric's f(wo, wi); *pdf: the density of sampling wi from wo
 * (rough_dielectric_sample). */
inline float rough_dielectric_eval(float3 wo, float3 wi, float eta, Ggx a, bool radiance, float* pdf) {
  *pdf = 0.0f;
  float co = wo.z, ci = wi.z;
  if (co == 0.0f || ci == 0.0f) return 0.0f;
  bool reflect = co * ci > 0.0f;
  float etap = reflect ? 1.0f : (co > 0.0f ? eta : 1.0f / eta);
  float3 wm = wi * etap + wo;
  if (dot(wm, wm) == 0.0f) return 0.0f;
  wm = normalize(wm);
  if (wm.z < 0.0f) wm = -wm;
  /* Facets seen from behind by either direction take no part. */
  if (dot(wm, wi) * ci < 0.0f || dot(wm, wo) * co < 0.0f) return 0.0f;
  float F = facet_fresnel(dot(wo, wm), eta);
  float D = ggx_d(a, wm), G = ggx_g(a, wo, wi);
  if (reflect) {
    *pdf = ggx_visible_pdf(a, wo, wm) / (4.0f * fabs(dot(wo, wm))) * F;
    return D * G * F / fabs(4.0f * ci * co);
  }
  float denom = dot(wi, wm) + dot(wo, wm) / etap;
  denom *= denom;
  *pdf = ggx_visible_pdf(a, wo, wm) * fabs(dot(wi, wm)) / denom * (1.0f - F);
  float f = D * (1.0f - F) * G * fabs(dot(wi, wm) * dot(wo, wm) / (denom * ci * co));
  return radiance ? f / (etap * etap) : f;
}

/* wi from wo: a visible normal, then reflection with probability F and refraction otherwise.
 * False where the sample is lost (it leaves on the wrong side, or meets total internal
 * reflection at a facet that reflection did not choose). */
inline bool rough_dielectric_sample(float3 wo, float eta, Ggx a, bool radiance, float uc, float2 u,
                                    InterfaceSample* s) {
  if (wo.z == 0.0f) return false;
  float3 wm = ggx_sample_visible(a, wo, u);
  float cos_o = dot(wo, wm);
  float F = facet_fresnel(cos_o, eta);
  float G1 = ggx_g1(a, wo);
  if (uc < F) {
    float3 wi = reflect_about(wo, wm);
    if (wi.z * wo.z <= 0.0f) return false;
    s->wi = wi;
    s->pdf = ggx_visible_pdf(a, wo, wm) / (4.0f * fabs(cos_o)) * F;
    s->weight = ggx_g(a, wo, wi) / G1;
    s->transmitted = false;
    s->cos_m = fabs(cos_o);
    return true;
  }
  /* Refraction through the facet, from wo's side to the other. */
  float3 n = cos_o >= 0.0f ? wm : -wm;
  float etap = cos_o >= 0.0f ? eta : 1.0f / eta;
  float ci_m = fabs(cos_o);
  float sin2_t = (1.0f - ci_m * ci_m) / (etap * etap);
  if (sin2_t >= 1.0f) return false;
  float3 wi = -wo / etap + (ci_m / etap - sqrt(1.0f - sin2_t)) * n;
  wi = normalize(wi);
  if (wi.z * wo.z >= 0.0f) return false;
  float denom = dot(wi, wm) + cos_o / etap;
  denom *= denom;
  s->wi = wi;
  s->pdf = ggx_visible_pdf(a, wo, wm) * fabs(dot(wi, wm)) / denom * (1.0f - F);
  float w = ggx_g(a, wo, wi) / G1;
  s->weight = radiance ? w / (etap * etap) : w;
  s->transmitted = true;
  s->cos_m = ci_m;
  return true;
}

/* A rough conductor's f(wo, wi) without F; *pdf as for rough_conductor_sample, *cos_m: F's
 * argument. Both directions on the same side. */
inline float rough_conductor_eval(float3 wo, float3 wi, Ggx a, float* pdf, float* cos_m) {
  *pdf = 0.0f;
  float co = wo.z, ci = wi.z;
  if (co * ci <= 0.0f) return 0.0f;
  float3 wm = wi + wo;
  if (dot(wm, wm) == 0.0f) return 0.0f;
  wm = normalize(wm);
  if (wm.z < 0.0f) wm = -wm;
  *cos_m = fabs(dot(wo, wm));
  *pdf = ggx_visible_pdf(a, wo, wm) / (4.0f * *cos_m);
  return ggx_d(a, wm) * ggx_g(a, wo, wi) / fabs(4.0f * ci * co);
}

inline bool rough_conductor_sample(float3 wo, Ggx a, float2 u, InterfaceSample* s) {
  if (wo.z == 0.0f) return false;
  float3 wm = ggx_sample_visible(a, wo, u);
  float3 wi = reflect_about(wo, wm);
  if (wi.z * wo.z <= 0.0f) return false;
  s->wi = wi;
  s->cos_m = fabs(dot(wo, wm));
  s->pdf = ggx_visible_pdf(a, wo, wm) / (4.0f * s->cos_m);
  s->weight = ggx_g(a, wo, wi) / ggx_g1(a, wo);
  s->transmitted = false;
  return true;
}

#endif
