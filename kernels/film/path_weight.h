/* The colour of a camera path (docs/design.md#why-transport-stays-compact): the linear map T from spectral radiance arriving at the
 * current vertex to the pixel's film rows. Diagonal mode T = C∘w (N values) until the first
 * fluorescent bounce, then rank-1 mode T = c bᵀ (R + N values, b kept at max 1). With
 * KASHA_FULL_MATRIX (a test-only reference) T is carried as the full R×N matrix instead.
 * Spectra it is applied to stay in global memory: T·(y∘z) for two of them (null for ones).
 * Defines: KASHA_BINS (N), KASHA_FILM_ROWS (R), KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE. */
#ifndef KASHA_PATH_WEIGHT_H
#define KASHA_PATH_WEIGHT_H

#include "film/film_view.h"
#include "materials/coated_conductor.h"

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

#define PW_FACTOR(v, i) ((v) ? (v)[i] : 1.0f)

inline void pw_init(PathWeight* p, const FilmView* f) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i)
      p->T[r][i] = KASHA_SPECTRAL_FILM ? (r == i ? 1.0f : 0.0f) : f->cmf[r * KASHA_BINS + i];
#else
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] = 1.0f;
#if KASHA_FLUORESCENCE
  p->rank1 = false;
#endif
#endif
}

/* rows += scale · T·(y∘z) */
inline void pw_add(const PathWeight* p, const FilmView* f, const __global float* y, const __global float* z,
                   float scale, float* rows) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += p->T[r][i] * PW_FACTOR(y, i) * PW_FACTOR(z, i);
    rows[r] += scale * s;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float s = spectrum_dot(KASHA_BINS, p->b, y, z);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += scale * s * p->c[r];
    return;
  }
#endif
  film_rows(f, p->w, y, z, scale, rows);
#endif
}

/* Energy the path would carry to the film under equal-energy light after scattering by diag(d)
 * (d null: the identity): Σ_i u_i w_i d_i in diagonal mode, Σ_i b_i d_i in rank-1 mode (c is
 * common to every branch), Σ_ri T_ri d_i for the full matrix. */
inline float pw_energy(const PathWeight* p, const FilmView* f, const __global float* d) {
#if KASHA_FULL_MATRIX
  float s = 0.0f;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) s += p->T[r][i] * PW_FACTOR(d, i);
  return s;
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) return spectrum_dot(KASHA_BINS, p->b, d, 0);
#endif
  return spectrum_dot(KASHA_BINS, p->w, f->importance, d);
#endif
}

/* Bin i's share of pw_energy(p, f, 0). */
inline float pw_bin_energy(const PathWeight* p, const FilmView* f, int i) {
#if KASHA_FULL_MATRIX
  float s = 0.0f;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) s += p->T[r][i];
  return s;
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) return p->b[i];
#endif
  return p->w[i] * f->importance[i];
#endif
}

/* How much the path still carries: the film rows' total response to equal-energy radiance,
 * Σ_r (T·1)_r, with the branch importance u standing in for the rows in diagonal mode (and
 * weighing the rows of a spectral film in rank-1 mode, so both modes measure alike). Russian
 * roulette compares it with its value at the camera, Σ_i u_i. */
inline float pw_magnitude(const PathWeight* p, const FilmView* f) {
#if KASHA_FULL_MATRIX
  return pw_energy(p, f, 0);
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
#if KASHA_SPECTRAL_FILM
    /* The rows are bins: weighed by their importance, as diagonal mode weighs them. */
    float c = spectrum_dot(KASHA_BINS, p->c, f->importance, 0);
#else
    float c = 0.0f;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) c += p->c[r];
#endif
    return c * spectrum_dot(KASHA_BINS, p->b, 0, 0);
  }
#endif
  return spectrum_dot(KASHA_BINS, p->w, f->importance, 0);
#endif
}

/* T ← T·diag(d)·scale: a passive bounce (d = ρ), or a gloss bounce (d null: white). */
inline void pw_scatter_diagonal(PathWeight* p, const __global float* d, float scale) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] *= scale * PW_FACTOR(d, i);
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    /* Scale goes to c; b stays normalized to a maximum of 1. */
    float m = 1.0f;
    if (d) {
      m = 0.0f;
      for (int i = 0; i < KASHA_BINS; ++i) m = fmax(m, p->b[i] *= d[i]);
      if (m > 0.0f)
        for (int i = 0; i < KASHA_BINS; ++i) p->b[i] /= m;
    }
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= scale * m;
    return;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] *= scale * PW_FACTOR(d, i);
#endif
}

#if KASHA_DISPERSION
/* At the path's first dispersive interface: one bin j chosen in proportion to the energy each bin
 * carries to the film under equal-energy light (as pw_energy), u uniform in [0, 1); every other
 * bin's column of T is dropped and j's divided by its probability, so the path goes on as a
 * single-bin path (docs/materials.md#dispersion). -1 when the path carries nothing. */
inline int pw_choose_bin(PathWeight* p, const FilmView* f, float u) {
  float total = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) total += pw_bin_energy(p, f, i);
  if (!(total > 0.0f)) return -1;
  float target = u * total, sum = 0.0f, e = 0.0f;
  int j = -1;
  for (int i = 0; i < KASHA_BINS; ++i) {
    float ei = pw_bin_energy(p, f, i);
    if (ei <= 0.0f) continue;
    j = i;
    e = ei;
    sum += ei;
    if (sum > target) break;
  }
  float scale = total / e;
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] = i == j ? p->T[r][i] * scale : 0.0f;
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    /* b_j becomes 1 (b stays normalized to a maximum of 1): its value and 1/p_j go to c. */
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= p->b[j] * scale;
    for (int i = 0; i < KASHA_BINS; ++i) p->b[i] = i == j ? 1.0f : 0.0f;
    return j;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] = i == j ? p->w[i] * scale : 0.0f;
#endif
  return j;
}
#endif

#if KASHA_CONDUCTOR
/* rows += scale · T·(y∘F): light y through a conductor whose reflectance F (bare or under `coat`,
 * coated_conductor.h) is computed bin by bin at the cosine cos_m (next-event estimation at a rough
 * conductor). */
inline void pw_add_conductor(const PathWeight* p, const FilmView* f, const __global float* y, const __global float* eta,
                             const __global float* k, float4 coat, float cos_m, float scale, float* rows) {
#if KASHA_FULL_MATRIX
  for (int i = 0; i < KASHA_BINS; ++i) {
    float v = scale * PW_FACTOR(y, i) * conductor_reflectance(cos_m, eta[i], k[i], coat);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += p->T[r][i] * v;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += p->b[i] * PW_FACTOR(y, i) * conductor_reflectance(cos_m, eta[i], k[i], coat);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += scale * s * p->c[r];
    return;
  }
#endif
  film_rows_conductor(f, p->w, y, eta, k, coat, cos_m, scale, rows);
#endif
}

/* T ← T·diag(F): a smooth conductor's reflection, F_i its reflectance in bin i at the cosine cos_i
 * (bare or under `coat`, coated_conductor.h), computed bin by bin so no spectrum is held in
 * private memory. */
inline void pw_scatter_conductor(PathWeight* p, const __global float* eta, const __global float* k, float4 coat,
                                 float cos_i) {
#if KASHA_FULL_MATRIX
  for (int i = 0; i < KASHA_BINS; ++i) {
    float F = conductor_reflectance(cos_i, eta[i], k[i], coat);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->T[r][i] *= F;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float m = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) m = fmax(m, p->b[i] *= conductor_reflectance(cos_i, eta[i], k[i], coat));
    if (m > 0.0f)
      for (int i = 0; i < KASHA_BINS; ++i) p->b[i] /= m;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= m;
    return;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] *= conductor_reflectance(cos_i, eta[i], k[i], coat);
#endif
}
#endif

#if KASHA_FLUORESCENCE
/* T ← T·ê·aᵀ·scale: a fluorescent bounce. The result is rank-1 whatever T was. */
inline void pw_scatter_fluorescent(PathWeight* p, const FilmView* f, const __global float* ehat,
                                   const __global float* a, float scale) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float te = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) te += p->T[r][i] * ehat[i];
    for (int i = 0; i < KASHA_BINS; ++i) p->T[r][i] = scale * te * a[i];
  }
#else
  if (p->rank1) {
    float be = spectrum_dot(KASHA_BINS, p->b, ehat, 0);
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= scale * be;
  } else {
    /* c = C·(w∘ê) */
    film_rows_clear(p->c);
    film_rows(f, p->w, ehat, 0, scale, p->c);
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
