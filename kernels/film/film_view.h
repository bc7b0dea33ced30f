/* The film as every kernel sees it: the tables DeviceFilm uploads once in one buffer (the film
 * rows' weights C and the branch importance u per bin), and the job's ray counters (ray_counts: closest-hit and
 * shadow rays, two 32-bit words each, added to by add_ray_counts in hit_point.h). Kernels take
 * KASHA_FILM_PARAMS after the scene's and gather the tables into one FilmView with
 * KASHA_FILM_VIEW. Defines: KASHA_BINS, KASHA_FILM_ROWS, KASHA_SPECTRAL_FILM. */
#ifndef KASHA_FILM_VIEW_H
#define KASHA_FILM_VIEW_H

#include "materials/coated_conductor.h"
#include "shared/spectral_product.h"

typedef struct {
  const __global float* cmf;        /* 3 × N: x̄ȳz̄ of each bin times its width */
  const __global float* importance; /* N: what a bin is worth to the film, for branch choices */
} FilmView;

/* film_tables: C (3 × N), then the importance (N). */
#define KASHA_FILM_PARAMS __global const float *film_tables, __global uint *ray_counts
#define KASHA_FILM_VIEW(name) FilmView name = {film_tables, film_tables + 3 * KASHA_BINS}

/* rows += scale · C·(x∘y∘z), each factor null for ones (spectral_product.h). */
inline void film_rows(const FilmView* f, const float* x, const __global float* y, const __global float* z,
                      float scale, float* rows) {
  film_rows_add(f->cmf, KASHA_SPECTRAL_FILM, KASHA_BINS, x, y, z, scale, rows);
}

#if KASHA_CONDUCTOR
/* rows += scale · C·(x∘y∘F), F a conductor's reflectance in each bin at the cosine cos_m, bare or
 * under the coat `coat` (coated_conductor.h), computed bin by bin. */
inline void film_rows_conductor(const FilmView* f, const float* x, const __global float* y, const __global float* eta,
                                const __global float* k, float4 coat, float cos_m, float scale, float* rows) {
  for (int i = 0; i < KASHA_BINS; ++i) {
    float v = scale * (x ? x[i] : 1.0f) * (y ? y[i] : 1.0f) * conductor_reflectance(cos_m, eta[i], k[i], coat);
#if KASHA_SPECTRAL_FILM
    rows[i] += v;
#else
    rows[0] += f->cmf[i] * v;
    rows[1] += f->cmf[KASHA_BINS + i] * v;
    rows[2] += f->cmf[2 * KASHA_BINS + i] * v;
#endif
  }
}
#endif

inline void film_rows_clear(float* rows) {
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] = 0.0f;
}

/* Whether a sample's rows are all finite (a sample that is not is left out and counted). */
inline bool film_rows_finite(const float* rows) {
  bool finite = true;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) finite = finite && isfinite(rows[r]);
  return finite;
}

/* Adds a work item's rows to its own pixel of a pass's per-pixel sums (no other item writes
 * there, so no atomics). */
inline void film_add(__global float* sums, int pixel, const float* rows) {
  __global float* cell = sums + (long)pixel * KASHA_FILM_ROWS;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) cell[r] += rows[r];
}

#endif
