/* A hit point's material as the kernels use it: pointers to its spectra in global memory (the
 * scene's zero spectrum for an absent part), so nothing of size N is copied per vertex.
 * Defines: KASHA_BINS, KASHA_FLUORESCENCE, KASHA_GLOSS, and KASHA_DIELECTRIC, KASHA_CONDUCTOR,
 * KASHA_DISPERSION, KASHA_ROUGH, KASHA_COATED (0 where the scene has no such material: the kernels carry no
 * code for it). */
#ifndef KASHA_SURFACE_H
#define KASHA_SURFACE_H

#include "materials/microfacet.h"
#include "geometry/scene_view.h"

#ifndef KASHA_COATED
#define KASHA_COATED 0
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
#if KASHA_DISPERSION
  const __global float* eta_bins; /* a dispersive dielectric's eta per bin */
  bool dispersive;
#endif
#if KASHA_CONDUCTOR
  const __global float* eta_c; /* the conductor's eta(lambda) and k(lambda) */
  const __global float* k_c;
#endif
#if KASHA_ROUGH
  Ggx alpha; /* a rough dielectric's or conductor's roughness; (0, 0) when smooth */
#endif
#if KASHA_COATED
  bool coated;          /* a coat over the Lambert parts (coat.h; set up there by coat_at) */
  const __global float* coat_table; /* a rough coat's E(μ) and t(μ) */
  float lambert_out;    /* t(θ) / η² on the side the surface was met from */
  float lambert_albedo; /* t(θ) τ̄ / η² */
#endif
} Surface;

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
#endif
#if KASHA_COATED
  out->coated = m->coat_eta > 0.0f;
  out->coat_table = s->spectra + max(m->coat_table, 0);
  out->lambert_out = out->lambert_albedo = 1.0f;
#endif
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
