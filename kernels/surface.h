/* A hit point's material as the kernels use it: pointers to its spectra in global memory (the
 * scene's zero spectrum for an absent part), so nothing of size N is copied per vertex.
 * Defines: KASHA_BINS, KASHA_FLUORESCENCE, KASHA_GLOSS. */
#ifndef KASHA_SURFACE_H
#define KASHA_SURFACE_H

#include "scene_view.h"

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
}

inline bool surface_has_lambert(const Surface* s) {
#if KASHA_FLUORESCENCE
  return s->passive || s->fluorescent;
#else
  return s->passive;
#endif
}

#endif
