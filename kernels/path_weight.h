/* The colour of a camera path (DESIGN §1): the linear map T from spectral radiance arriving at the
 * current vertex to the pixel's film rows. Diagonal mode T = C∘w (N values) until the first
 * fluorescent bounce, then rank-1 mode T = c bᵀ (R + N values, b kept at max 1). With
 * KASHA_FULL_MATRIX (a test-only reference) T is carried as the full R×N matrix instead.
 * Defines: KASHA_BINS (N), KASHA_FILM_ROWS (R), KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE. */
#ifndef KASHA_PATH_WEIGHT_H
#define KASHA_PATH_WEIGHT_H

#include "film_rows.h"
#include "surface.h"

#ifndef KASHA_FULL_MATRIX
#define KASHA_FULL_MATRIX 0
#endif

typedef struct {
#if KASHA_FULL_MATRIX
  float T[KASHA_FILM_ROWS][KASHA_BINS];
#else
  float w[KASHA_BINS];
#if KASHA_FLUORESCENCE
  bool rank1;
  float c[KASHA_FILM_ROWS];
  float b[KASHA_BINS];
#endif
#endif
} PathWeight;

inline void pw_init(PathWeight* p, const __global float* cmf) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] = film_row_weight(cmf, r, i);
#else
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] = 1.0f;
#if KASHA_FLUORESCENCE
  p->rank1 = false;
#endif
#endif
}

/* rows += scale · T·v */
inline void pw_add(const PathWeight* p, const __global float* cmf, const float* v, float scale, float* rows) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += p->T[r][i] * v[i];
    rows[r] += scale * s;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += p->b[i] * v[i];
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += scale * s * p->c[r];
    return;
  }
#endif
#if KASHA_SPECTRAL_FILM
  for (int i = 0; i < KASHA_BINS; ++i) rows[i] += scale * p->w[i] * v[i];
#else
  for (int r = 0; r < 3; ++r) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += cmf[r * KASHA_BINS + i] * p->w[i] * v[i];
    rows[r] += scale * s;
  }
#endif
#endif
}

/* Energy the path would carry to the film under equal-energy light after scattering by diag(d)
 * (or, for d == 0, the identity): Σ_i u_i w_i d_i in diagonal mode, Σ_i b_i d_i in rank-1 mode
 * (c is common to every branch), Σ_ri T_ri d_i for the full matrix. */
inline float pw_energy(const PathWeight* p, const __global float* importance, const float* d) {
  float s = 0.0f;
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) s += p->T[r][i] * (d ? d[i] : 1.0f);
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    for (int i = 0; i < KASHA_BINS; ++i) s += p->b[i] * (d ? d[i] : 1.0f);
    return s;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) s += importance[i] * p->w[i] * (d ? d[i] : 1.0f);
#endif
  return s;
}

/* T ← T·diag(d)·scale: a passive bounce (d = ρ), or a gloss bounce (d == 0: white). */
inline void pw_scatter_diagonal(PathWeight* p, const float* d, float scale) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] *= scale * (d ? d[i] : 1.0f);
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    /* Scale goes to c; b stays normalized to a maximum of 1. */
    float m = 0.0f;
    if (d) {
      for (int i = 0; i < KASHA_BINS; ++i) m = fmax(m, p->b[i] *= d[i]);
      if (m > 0.0f)
        for (int i = 0; i < KASHA_BINS; ++i) p->b[i] /= m;
    } else {
      m = 1.0f;
    }
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= scale * m;
    return;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] *= scale * (d ? d[i] : 1.0f);
#endif
}

#if KASHA_FLUORESCENCE
/* T ← T·ê·aᵀ·scale: a fluorescent bounce. The result is rank-1 whatever T was. */
inline void pw_scatter_fluorescent(PathWeight* p, const __global float* cmf, const float* ehat, const float* a,
                                   float scale) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float te = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) te += p->T[r][i] * ehat[i];
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] = scale * te * a[i];
  }
#else
  if (p->rank1) {
    float be = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) be += p->b[i] * ehat[i];
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= scale * be;
  } else {
    /* c = C·(w∘ê), b = a */
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] = 0.0f;
    float rows_tmp[KASHA_FILM_ROWS];
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows_tmp[r] = 0.0f;
    pw_add(p, cmf, ehat, scale, rows_tmp);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] = rows_tmp[r];
    p->rank1 = true;
  }
  float m = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) m = fmax(m, p->b[i] = a[i]);
  if (m > 0.0f) {
    for (int i = 0; i < KASHA_BINS; ++i) p->b[i] /= m;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= m;
  }
#endif
}

#endif

#endif
