/* A camera path's flight through scattering media (docs/media.md#scattering): where along its ray
 * the path next scatters in a medium, or that it reaches the next surface. kasha's paths carry
 * every bin at once while σt varies with wavelength, so one distance is drawn for all of them by
 * one-sample MIS over the bins (the balance heuristic, as hero-wavelength sampling does): a bin j
 * is chosen by the energy c_j the path carries in it, and the distance by bin j's optical depth,
 * exp(−τ_j); each bin i is then weighed by its own density over the mixture's,
 *   at a collision in medium m:   T_i(t) / Σ_k c_k σt_k(m) T_k(t)  (times σs_i, or a fluorophore's
 *                                 absorption, by the event the vertex chooses),
 *   on reaching the surface:      T_i(d) / Σ_k c_k T_k(d),
 * with T the transmittance over every medium crossed (interfaces passed through on the way). The
 * weights stay bounded wherever a bin carries energy, and the estimate is unbiased in every bin. */
#ifndef KASHA_MEDIUM_FLIGHT_H
#define KASHA_MEDIUM_FLIGHT_H

#include "film/path_weight.h"
#include "geometry/hit_point.h"
#include "materials/hit_material.h"
#include "media/medium.h"
#include "media/medium_emission.h"

#if KASHA_MEDIA
/* T ← T·diag(tr)·scale (b kept normalised to a maximum of 1 in rank-1 mode, path_weight.h). */
inline void pw_transmit_bins(PathWeight* p, const float* tr, float scale) {
#if KASHA_FULL_MATRIX
  for (int i = 0; i < KASHA_BINS; ++i) {
    float v = tr[i] * scale;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->T[r][i] *= v;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float mx = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) mx = fmax(mx, p->b[i] *= tr[i]);
    if (mx > 0.0f)
      for (int i = 0; i < KASHA_BINS; ++i) p->b[i] /= mx;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) p->c[r] *= mx * scale;
    return;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->w[i] *= tr[i] * scale;
#endif
}

/* T ← T·diag(T_i)·scale, T_i the trail's transmittance in bin i. */
inline void pw_transmit(PathWeight* p, const SceneView* s, const MediaTrail* t, float scale) {
  float tr[KASHA_BINS];
  trail_bins(s, t, tr);
  pw_transmit_bins(p, tr, scale);
}
#endif

/* Where a flight ends. */
#define KASHA_FLIGHT_ESCAPED 0
#define KASHA_FLIGHT_SURFACE 1
#define KASHA_FLIGHT_SCATTERED 2

#if KASHA_SCATTERING

/* σt per bin at the latest collision in medium m (a component grid's: collision_coefficients'). */
inline const __global float* medium_extinction(const SceneView* s, const __global KMedium* m) {
#if KASHA_GRID_COMPONENTS
  if (m->components > 0) return s->scratch + KASHA_SCRATCH_COMPONENTS;
#endif
  return s->spectra + m->sigma_t;
}

/* σs per bin at the latest collision in m, likewise. */
inline const __global float* medium_scattering(const SceneView* s, const __global KMedium* m) {
#if KASHA_GRID_COMPONENTS
  if (m->components > 0) return s->scratch + KASHA_SCRATCH_COMPONENTS + KASHA_BINS;
#endif
  return s->spectra + m->sigma_s;
}

/* A collision at x in medium m: a component grid's coefficients there into scratch slot 0, which
 * medium_extinction and medium_scattering read until the path's next collision. */
inline void collision_coefficients(const SceneView* s, int m, float3 x) {
#if KASHA_GRID_COMPONENTS
  if (s->media[m].components > 0) components_at(s, &s->media[m], x, 0);
#endif
}

/* T ← T·diag(T_i)/Σ_k c_k u_k: the flight's weight, with u_k = σt_k(m) T_k at a collision in medium
 * m (m ≥ 0) and T_k on reaching a surface or leaving the scene (m < 0), c_k = e_k / total the bins'
 * energy shares before the flight. What the collision does (σs, or a fluorophore's absorption) is
 * the vertex's (walk_medium_vertex). A path whose mixture density is 0 carries nothing on. Returns
 * T̄, the mean of T_i over the bins (vcm's pseudo-density of the segment, vcm_media.h). */
inline float pw_flight(PathWeight* p, const SceneView* s, const FilmView* f, const MediaTrail* t, int m, float total) {
  float tr[KASHA_BINS], den = 0.0f;
  float tbar = trail_bins(s, t, tr);
  const __global float* sigma_t = m >= 0 ? medium_extinction(s, &s->media[m]) : 0;
  for (int k = 0; k < KASHA_BINS; ++k) {
    float e = pw_bin_energy(p, f, k);
    if (e > 0.0f) den += e * tr[k] * (sigma_t ? sigma_t[k] : 1.0f);
  }
  den /= total;
  pw_transmit_bins(p, tr, den > 0.0f ? 1.0f / den : 0.0f);
  return tbar;
}

/* The bin the flight's distance follows: chosen on u by the energy each bin carries (pw_bin_energy),
 * whose sum is *total; -1 when the path carries nothing. */
inline int flight_bin(const PathWeight* p, const FilmView* f, float u, float* total) {
  float sum = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) sum += pw_bin_energy(p, f, i);
  *total = sum;
  if (!(sum > 0.0f)) return -1;
  float target = u * sum, run = 0.0f;
  int j = -1;
  for (int i = 0; i < KASHA_BINS; ++i) {
    float e = pw_bin_energy(p, f, i);
    if (e <= 0.0f) continue;
    j = i;
    run += e;
    if (run > target) break;
  }
  return j;
}

/* How far along the ray it leaves the scene's bounding sphere (0 if it never meets it). A ray with
 * no surface ahead collides only that far: an unbounded medium is taken to end there, so a path
 * that leaves the scene does not wander on without end (one slipped through a crack between
 * triangles neither). What leaves sees nothing, as before. */
inline float beyond_scene(const SceneView* s, float3 org, float3 dir) {
  float3 c = org - s->bounds.xyz;
  float b = dot(c, dir), disc = b * b - (dot(c, c) - s->bounds.w * s->bounds.w);
  return disc > 0.0f ? fmax(-b + sqrt(disc), 0.0f) : 0.0f;
}

#if KASHA_MEDIUM_GRIDS
/* A flight's piece through grid medium m (index `medium`), org + t dir for t in [0, len]: the t
 * where bin j's optical depth reaches *depth, or -1 with *depth lessened by the piece's (never
 * below 0); the piece's optical lengths, up to where it stopped, onto the trail. */
inline float grid_flight(const SceneView* s, const __global KMedium* m, int medium, float3 org,
                         float3 dir, float len, int j, float* depth, MediaTrail* trail) {
  float at;
#if KASHA_GRID_COMPONENTS
  if (m->components > 0) {
    float w[KASHA_GRID_COMPONENTS], sums[KASHA_GRID_COMPONENTS];
    for (int k = 0; k < m->components; ++k)
      w[k] = s->spectra[m->sigma_t + k * KASHA_BINS + j], sums[k] = 0.0f;
    float used = components_march(s, m, org, dir, len, w, *depth, sums, &at);
    trail_add_components(trail, m, medium, sums);
    if (at < 0.0f) *depth = fmax(*depth - used, 0.0f);
    return at;
  }
#endif
  float sigma = s->spectra[m->sigma_t + j];
  float optical = grid_march(s, m, org, dir, len, sigma > 0.0f ? *depth / sigma : -1.0f, &at);
  trail_add(trail, medium, optical);
  if (at < 0.0f) *depth = fmax(*depth - sigma * optical, 0.0f);
  return at;
}
#endif

/* The distance part of the flight, shared by camera paths and photons: from org along dir in
 * *medium, through interfaces, to where bin j's optical depth reaches `depth` (KASHA_FLIGHT_SCATTERED,
 * h->x the point, in *medium as the walk left it), or the next surface
 * (KASHA_FLIGHT_SURFACE, h its hit) or nothing (KASHA_FLIGHT_ESCAPED). The lengths crossed in each
 * medium go on the trail; h->t is the distance travelled. */
inline int flight_walk(const SceneView* s, float3 org, float3 dir, int* medium, int j, float depth, MediaTrail* trail,
                       HitPoint* h) {
  trail_clear(trail);
  float travelled = 0.0f;
  for (int k = 0; k < KASHA_MAX_INTERFACES; ++k) {
    bool hit = intersect_surface(s, org, dir, h);
    float len = hit ? h->t : INFINITY,
          sigma = *medium >= 0 ? s->spectra[s->media[*medium].sigma_t + j] : 0.0f;
#if KASHA_MEDIUM_GRIDS
    const __global KMedium* grid = *medium >= 0 && s->media[*medium].density >= 0 ? &s->media[*medium] : 0;
    if (grid) {
      /* Where bin j's optical depth reaches `depth` (density_grid.h, colour_grid.h). */
      float at = grid_flight(s, grid, *medium, org, dir, len, j, &depth, trail);
      if (at >= 0.0f) {
        float t = hit ? fmax(fmin(at, len - h->eps), 0.0f) : at;
        h->x = org + t * dir;
        h->t = travelled + t;
        return KASHA_FLIGHT_SCATTERED;
      }
    } else
#endif
    if (sigma > 0.0f && depth < sigma * (hit ? len : beyond_scene(s, org, dir))) {
      /* Kept off the surface ahead by its offset: a point rounded onto its far side would leave
       * the medium through the surface (and, outside a closed one, wander without end). */
      float t = hit ? fmax(fmin(depth / sigma, len - h->eps), 0.0f) : depth / sigma;
      trail_add(trail, *medium, t);
      h->x = org + t * dir;
      h->t = travelled + t;
      return KASHA_FLIGHT_SCATTERED;
    } else {
      if (sigma > 0.0f) depth -= sigma * len;
      trail_add(trail, *medium, len);
    }
    if (hit) travelled += h->t;
    if (!hit || !hit_interface(s, h)) {
      h->t = travelled;
      return hit ? KASHA_FLIGHT_SURFACE : KASHA_FLIGHT_ESCAPED;
    }
    org = cross_interface(s, h, dir, medium);
  }
  return KASHA_FLIGHT_ESCAPED;
}

/* Bin j's optical depth to the scattering, drawn on u (exponential). */
inline float flight_depth(float u) {
  return -log(1.0f - fmin(u, 0x1.fffffep-1f));
}

/* From org along dir in *medium, through interfaces: KASHA_FLIGHT_SCATTERED with h->x the point
 * in *medium where the path scatters, KASHA_FLIGHT_SURFACE with the surface hit h, or
 * KASHA_FLIGHT_ESCAPED; the path's colour weighed as above (u: the bin choice and the distance).
 * h->t is the distance travelled, *tbar the mean over the bins of the flight's transmittance (1
 * where the path carried nothing). */
inline int flight(PathWeight* p, const SceneView* s, const FilmView* f, float3 org, float3 dir, int* medium,
                  float2 u, HitPoint* h, float* tbar) {
  float total;
  MediaTrail trail;
  *tbar = 1.0f;
  int j = flight_bin(p, f, u.x, &total);
  if (j < 0) return KASHA_FLIGHT_ESCAPED;
  int reached = flight_walk(s, org, dir, medium, j, flight_depth(u.y), &trail, h);
  if (reached == KASHA_FLIGHT_SCATTERED) collision_coefficients(s, *medium, h->x);
  *tbar = pw_flight(p, s, f, &trail, reached == KASHA_FLIGHT_SCATTERED ? *medium : -1, total);
  return reached;
}

#if KASHA_MEDIUM_EMISSION
/* rows += scale · the path's weight ∘ e, e a spectrum in registers (N floats; changed). */
inline void pw_add_private(const PathWeight* p, const FilmView* f, float* e, float scale, float* rows) {
#if KASHA_FULL_MATRIX
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float sum = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) sum += p->T[r][i] * e[i];
    rows[r] += scale * sum;
  }
#else
#if KASHA_FLUORESCENCE
  if (p->rank1) {
    float sum = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) sum += p->b[i] * e[i];
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += scale * sum * p->c[r];
    return;
  }
#endif
  for (int i = 0; i < KASHA_BINS; ++i) e[i] *= p->w[i];
  film_rows(f, e, 0, 0, scale, rows);
#endif
}

/* A camera path's collision at x in `medium` picks up what the medium emits there (docs/media.md
 * #emitting-media): σa·Le over the flight's density (which the flight's weight divides out),
 * times an emitting grid's scale at x, with a temperature grid's blackbody in Le's place; in a
 * colour grid σa(x) Le(x) (media/medium_emission.h). */
inline void medium_emission_add(const PathWeight* p, const SceneView* s, const FilmView* f, int medium, float3 x,
                                float* rows) {
  const __global KMedium* m = &s->media[medium];
  if (m->emission < 0) return;
  float e[KASHA_BINS];
  medium_emission_per_density(s, m, x, 1.0f, e);
  pw_add_private(p, f, e, 1.0f, rows);
}
#endif
#endif

#endif
