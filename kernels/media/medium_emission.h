/* What an emitting medium emits at a point (docs/media.md#emitting-media): σa·Le per bin, the
 * KMedium's `emission` spectrum, times a grid's density, its emission scale there and, with a
 * temperature grid, the blackbody of the temperature there in Le's place; in a colour grid σa(x)
 * times its radiance Le(x), both sums of components (colour_grid.h). Camera paths take it over
 * their collision's density (transport/medium_flight.h: a density grid's density cancels); light
 * paths that start in the medium (transport/medium_light.h) take it whole. */
#ifndef KASHA_MEDIUM_EMISSION_H
#define KASHA_MEDIUM_EMISSION_H

#include "geometry/scene_view.h"
#include "media/colour_grid.h"
#include "media/density_grid.h"

#ifndef KASHA_MEDIUM_EMISSION
#define KASHA_MEDIUM_EMISSION 0
#endif
#ifndef KASHA_MEDIUM_BLACKBODY
#define KASHA_MEDIUM_BLACKBODY 0
#endif

#if KASHA_MEDIA && KASHA_MEDIUM_EMISSION
#if KASHA_MEDIUM_BLACKBODY
/* pbrt-v4's BlackbodySpectrum: Planck's law at nm and T kelvin over its value at Wien's peak, a
 * function of λT alone: (b / λT)^5 (e^(c2/b) − 1) / (e^(c2/λT) − 1). */
inline float blackbody_normalized(float nm, float T) {
  const float b = 2.8977721e-3f, c2 = 1.4387769e-2f, peak = 142.32146f; /* e^(c2/b) − 1 */
  float x = nm * 1e-9f * T, r = b / x;
  return r * r * r * r * r * peak / (exp(c2 / x) - 1.0f);
}

/* Bin i's blackbody: its mean at the bin's two Gauss nodes. */
inline float blackbody_bin(const SceneView* s, const __global KMedium* m, int i, float T) {
  const __global float* node = s->spectra + m->bin_nodes;
  return 0.5f * (blackbody_normalized(node[2 * i], T) + blackbody_normalized(node[2 * i + 1], T));
}
#endif

#if KASHA_GRID_COMPONENTS
/* out[i] = scale · σa_i(x) Le_i(x) in a colour grid that emits (pbrt-v4's rgbgrid "Le"): σa summed
 * over its components (σt_k − σs_k is exact per component: a σa colour's or 0), Le trilinear in
 * its radiance components (KMedium::emission_components). */
inline void colour_emission_at(const SceneView* s, const __global KMedium* m, float3 x, float scale, float* out) {
  float3 q = grid_map(m, x, 1.0f), f = floor(q);
  int3 c = (int3)((int)f.x, (int)f.y, (int)f.z);
  int samples = m->grid_size[0] * m->grid_size[1] * m->grid_size[2];
  float le[KASHA_BINS];
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = 0.0f, le[i] = 0.0f;
  for (int k = 0; k < m->components; ++k) {
    float rho = component_trilinear(s, m, k, c, q);
    if (!(rho > 0.0f)) continue;
    const __global float* st = s->spectra + m->sigma_t + k * KASHA_BINS;
    const __global float* ss = s->spectra + m->sigma_s + k * KASHA_BINS;
    for (int i = 0; i < KASHA_BINS; ++i) out[i] += rho * (st[i] - ss[i]);
  }
  for (int j = 0; j < m->emission_components; ++j) {
    float w = grid_trilinear_in(s, m, m->emission_scale + j * samples, c.x, c.y, c.z, q);
    if (!(w > 0.0f)) continue;
    const __global float* e = s->spectra + m->emission + j * KASHA_BINS;
    for (int i = 0; i < KASHA_BINS; ++i) le[i] += w * e[i];
  }
  for (int i = 0; i < KASHA_BINS; ++i) out[i] *= scale * le[i];
}
#endif

/* Whether m is a colour grid that emits, whose emission colour_emission_at gives. */
inline bool colour_emission(const __global KMedium* m) {
#if KASHA_GRID_COMPONENTS
  return m->emission_components > 0;
#else
  return false;
#endif
}

/* The factor on m's emission at x beyond its density: an emitting grid's scale there, 1
 * elsewhere. *T: the temperature whose blackbody takes Le's place (0 where there is none; a
 * temperature at or below pbrt-v4's cutoff of 100 K emits nothing: factor 0). */
inline float medium_emission_factor(const SceneView* s, const __global KMedium* m, float3 x, float* T) {
  *T = 0.0f;
  float scale = 1.0f;
#if KASHA_MEDIUM_GRIDS
  if (m->density >= 0 && (m->emission_scale >= 0 || m->temperature >= 0)) {
    float3 q = grid_map(m, x, 1.0f);
    if (m->emission_scale >= 0) scale = grid_value_at(s, m, m->emission_scale, q);
#if KASHA_MEDIUM_BLACKBODY
    if (m->temperature >= 0) {
      *T = (grid_value_at(s, m, m->temperature, q) - m->temperature_offset) * m->temperature_scale;
      if (!(*T > 100.0f)) scale = 0.0f;
    }
#endif
  }
#endif
  return scale;
}

/* out[i] = scale · what m emits at x in bin i (per unit length and solid angle) over a density
 * grid's density there, which a camera path's collision weight cancels: σa·Le times the emission
 * factor and the blackbody, or a colour grid's σa(x) Le(x) (no density to cancel). */
inline void medium_emission_per_density(const SceneView* s, const __global KMedium* m, float3 x, float scale,
                                        float* out) {
#if KASHA_GRID_COMPONENTS
  if (colour_emission(m)) {
    colour_emission_at(s, m, x, scale, out);
    return;
  }
#endif
  float T;
  scale *= medium_emission_factor(s, m, x, &T);
  const __global float* em = s->spectra + m->emission;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = scale > 0.0f ? scale * em[i] : 0.0f;
#if KASHA_MEDIUM_BLACKBODY
  if (T > 0.0f && scale > 0.0f)
    for (int i = 0; i < KASHA_BINS; ++i) out[i] *= blackbody_bin(s, m, i, T);
#endif
}

/* out[i] = scale · what m emits at x in bin i, whole: the above times a density grid's density
 * (a light path's start, transport/medium_light.h). */
inline void medium_emission_at(const SceneView* s, const __global KMedium* m, float3 x, float scale, float* out) {
#if KASHA_MEDIUM_GRIDS
  if (m->density >= 0 && !colour_emission(m)) scale *= grid_density_at(s, m, grid_map(m, x, 1.0f));
#endif
  medium_emission_per_density(s, m, x, scale, out);
}
#endif

#endif
