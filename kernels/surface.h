/* A hit point's material on the wavelength grid, loaded into private memory once per vertex, and
 * the energies that choose its branch. Defines: KASHA_BINS, KASHA_FLUORESCENCE, KASHA_GLOSS. */
#ifndef KASHA_SURFACE_H
#define KASHA_SURFACE_H

#include "shared_types.h"

typedef struct {
  float rho[KASHA_BINS];
#if KASHA_FLUORESCENCE
  float a[KASHA_BINS];
  float ehat[KASHA_BINS];
  float a_sum;
  bool fluorescent;
#endif
  bool passive;
  float g;
  bool mirror;
} Surface;

inline void load_surface(const __global KMaterial* m, const __global float* spectra, Surface* s) {
  s->passive = m->passive >= 0;
  for (int i = 0; i < KASHA_BINS; ++i) s->rho[i] = s->passive ? spectra[m->passive + i] : 0.0f;
#if KASHA_FLUORESCENCE
  s->fluorescent = m->excitation >= 0;
  for (int i = 0; i < KASHA_BINS; ++i) {
    s->a[i] = s->fluorescent ? spectra[m->excitation + i] : 0.0f;
    s->ehat[i] = s->fluorescent ? spectra[m->emission + i] : 0.0f;
  }
  s->a_sum = m->excitation_sum;
#endif
  s->g = m->gloss;
  s->mirror = m->lobe < 0;
}

inline bool surface_has_lambert(const Surface* s) {
#if KASHA_FLUORESCENCE
  return s->passive || s->fluorescent;
#else
  return s->passive;
#endif
}

#endif
