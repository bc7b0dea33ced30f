/* A hit point's material as the kernels use it: pointers to its spectra in global memory (the
 * scene's zero spectrum for an absent part), so nothing of size N is copied per vertex.
 * Defines: KASHA_BINS, KASHA_FLUORESCENCE, KASHA_GLOSS, and KASHA_DIELECTRIC, KASHA_CONDUCTOR,
 * KASHA_DISPERSION, KASHA_ROUGH, KASHA_COATED, KASHA_TRANSMISSION, KASHA_THIN (0 where the scene has no such material: the kernels carry no
 * code for it). */
#ifndef KASHA_SURFACE_H
#define KASHA_SURFACE_H

#include "materials/microfacet.h"
#include "geometry/scene_view.h"

#ifndef KASHA_COATED
#define KASHA_COATED 0
#endif
#ifndef KASHA_TRANSMISSION
#define KASHA_TRANSMISSION 0
#endif
#ifndef KASHA_THIN
#define KASHA_THIN 0
#endif
/* Some used rough material has alpha_x != alpha_y: its frame follows ∂p/∂u (surface_frame). */
#ifndef KASHA_ANISOTROPIC
#define KASHA_ANISOTROPIC 0
#endif

typedef struct {
  const __global KMaterial* m;
  const __global float* rho;
#if KASHA_FLUORESCENCE
  const __global float* a;
  const __global float* ehat;
  float a_sum;
  bool fluorescent;
#endif
  bool passive;
  float g;
  bool mirror;
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
  int kind;
#endif
#if KASHA_DIELECTRIC
  float eta;
#endif
#if KASHA_THIN
  bool thin; /* a thin dielectric sheet: reflects or passes straight through (fresnel.h) */
#endif
#if KASHA_DISPERSION
  const __global float* eta_bins; /* a dispersive dielectric's eta per bin */
  bool dispersive;
#endif
#if KASHA_CONDUCTOR
  const __global float* eta_c; /* the conductor's eta(lambda) and k(lambda) */
  const __global float* k_c;
  /* A coated conductor's (coat index, thickness, under_coat, layer_scale); index 0: bare
   * (coated_conductor.h). */
  float4 coat_c;
#endif
#if KASHA_ROUGH
  Ggx alpha; /* a rough dielectric's or conductor's roughness; (0, 0) when smooth */
#endif
#if KASHA_ANISOTROPIC
  float3 dpdu; /* ∂p/∂u at the point, in world space: the x axis of alpha (pbrt-v4's frame) */
#endif
#if KASHA_COATED
  bool coated;          /* a coat over the Lambert parts (coat.h; set up there by coat_at) */
  const __global float* coat_table; /* a coat's E(μ) and t(μ) (coat.h) */
  float lambert_out;    /* t(θ) / η² on the side the surface was met from */
  float lambert_albedo; /* t(θ) τ̄ / η² */
#endif
#if KASHA_TRANSMISSION
  const __global float* tau; /* Lambert transmittance to the other side (the zero spectrum: none) */
  float share_t;             /* the share of the passive part's samples sent through; 0: none */
#endif
} Surface;

/* The frame a rough surface's GGX distribution lives in, about n (±the normal): x along ∂p/∂u
 * made orthogonal to n, y = n × x (pbrt-v4's Frame::FromXZ of the shading ∂p/∂u and n), so
 * alpha_x runs along the surface's u direction. Isotropic roughness needs no such x. */
inline Frame surface_frame(const Surface* surf, float3 n) {
#if KASHA_ANISOTROPIC
  float3 x = surf->dpdu - n * dot(n, surf->dpdu);
  float len = length(x);
  if (len > 1e-6f) {
    Frame f;
    f.n = n;
    f.s = x / len;
    f.t = cross(n, f.s);
    return f;
  }
#endif
  return frame_of(n);
}

inline void load_surface(const SceneView* s, int material, Surface* out) {
  const __global KMaterial* m = &s->materials[material];
  out->m = m;
  out->passive = m->passive >= 0;
  out->rho = s->spectra + max(m->passive, 0);
#if KASHA_FLUORESCENCE
  out->fluorescent = m->excitation >= 0;
  out->a = s->spectra + max(m->excitation, 0);
  out->ehat = s->spectra + max(m->emission, 0);
  out->a_sum = m->excitation_sum;
#endif
  out->g = m->gloss;
  out->mirror = m->lobe < 0;
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
  out->kind = m->kind;
#endif
#if KASHA_DIELECTRIC
  out->eta = m->eta;
#endif
#if KASHA_THIN
  out->thin = m->thin != 0;
#endif
#if KASHA_DISPERSION
  out->dispersive = m->kind == KASHA_KIND_DIELECTRIC && m->eta_spectrum >= 0;
  out->eta_bins = s->spectra + max(m->eta_spectrum, 0);
#endif
#if KASHA_ROUGH
  out->alpha.ax = m->alpha[0];
  out->alpha.ay = m->alpha[1];
#endif
#if KASHA_CONDUCTOR
  out->eta_c = s->spectra + max(m->eta_spectrum, 0);
  out->k_c = s->spectra + max(m->k_spectrum, 0);
  out->coat_c = (float4)(m->coat_eta, m->coat_thickness, (float)m->under_coat, m->layer_scale);
#endif
#if KASHA_COATED
  /* A conductor's coat is in its reflectance (coat_c), not over Lambert parts. */
  out->coated = m->coat_eta > 0.0f && m->kind == KASHA_KIND_MEASURED;
  out->coat_table = s->spectra + max(m->coat_table, 0);
  out->lambert_out = out->lambert_albedo = 1.0f;
#endif
#if KASHA_TRANSMISSION
  out->tau = s->spectra + max(m->transmittance, 0);
  out->share_t = m->transmit_share;
#endif
}

/* The passive part (pbrt-v4's DiffuseTransmissionBxDF where it transmits): ρ/π between
 * directions on one side of the surface, τ/π between directions on opposite sides. Its samples
 * go through with the material's constant share (host: mean τ / mean ρ + τ), so every
 * integrator's densities agree; these give the spectrum and share of either side. */
inline bool surface_transmits(const Surface* s) {
#if KASHA_TRANSMISSION
  return s->share_t > 0.0f;
#else
  return false;
#endif
}
inline float surface_side_share(const Surface* s, bool through) {
#if KASHA_TRANSMISSION
  if (s->share_t > 0.0f) return through ? s->share_t : 1.0f - s->share_t;
#endif
  return through ? 0.0f : 1.0f;
}
inline const __global float* surface_side_spectrum(const Surface* s, bool through) {
#if KASHA_TRANSMISSION
  if (through) return s->tau;
#endif
  return s->rho;
}

/* A dielectric or conductor interface: smooth (one delta lobe each way) or rough
 * (surface_rough); no Lambert part, nothing for the photon map. */
inline bool surface_specular(const Surface* s) {
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
  return s->kind != KASHA_KIND_MEASURED;
#else
  return false;
#endif
}

/* A dielectric or conductor with GGX microfacets (rough_interface.h): not a delta lobe, so
 * next-event estimation and MIS apply to it. */
inline bool surface_rough(const Surface* s) {
#if KASHA_ROUGH
  return s->alpha.ax >= KASHA_SMOOTH_ALPHA || s->alpha.ay >= KASHA_SMOOTH_ALPHA;
#else
  return false;
#endif
}

inline bool surface_has_lambert(const Surface* s) {
#if KASHA_FLUORESCENCE
  return s->passive || s->fluorescent;
#else
  return s->passive;
#endif
}

/* A dielectric's index where the scene has dielectrics, else 1. */
inline float surface_eta(const Surface* s) {
#if KASHA_DIELECTRIC
  return s->eta;
#else
  return 1.0f;
#endif
}

#endif
