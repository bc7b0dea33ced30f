/* A medium whose colour varies over its grid (docs/media.md#colour-grids; pbrt-v4's rgbgrid): σa
 * and σs given per sample as spectra, trilinear between samples. The host writes such a grid as
 * a few components, each a grid of non-negative weights ρ_k on the lattice with a spectrum of
 * its own (σt_k, σs_k per bin): σt(λ, x) = Σ_k ρ_k(x) σt_k(λ), σs likewise — the samples whose
 * colours are alike up to a factor share a component, or each bin is one where too many differ.
 * The sum is exact, so the tracking stays exact: a segment puts each component's ∫ ρ_k on the
 * trail (a slot each), bin i's optical depth is Σ_k σt_k,i ∫ ρ_k, and a free flight inverts bin
 * j's, whose integrand Σ_k σt_k,j ρ_k is one field (density_grid.h's grid_field).
 *
 * A component grid's σt and σs vary with the point, so a collision's coefficients are computed
 * there into the work item's scratch (slot 0: the latest collision of the path the work item
 * walks; slot 1: a stored light vertex a connection reaches), and the flight's weights take the
 * true coefficients: no density cancels, so a merge needs no 1/ρ. */
#ifndef KASHA_COLOUR_GRID_H
#define KASHA_COLOUR_GRID_H

#include "media/density_grid.h"

#ifndef KASHA_SCRATCH_COMPONENTS
#define KASHA_SCRATCH_COMPONENTS 0 /* where the two slots of σt, σs (2 N floats each) start */
#endif
/* Slots beyond the media's own one: Σ over the component grids of their components but one. */
#ifndef KASHA_TRAIL_SLOTS
#define KASHA_TRAIL_SLOTS KASHA_MEDIA_COUNT
#endif

#if KASHA_MEDIA && KASHA_MEDIUM_GRIDS && KASHA_GRID_COMPONENTS
/* out[k] = ∫ ρ_k over t in [a, b] along q0 + t dq, inside cell c, for each component. */
inline void components_cell_integrals(const SceneView* s, const __global KMedium* m, int3 c,
                                      float3 q0, float3 dq, float a, float b, float* out) {
  const float r = 0.28867513f; /* 1 / (2√3) */
  float h = b - a, mid = 0.5f * (a + b);
  float3 qa = q0 + (mid - r * h) * dq, qb = q0 + (mid + r * h) * dq;
  for (int k = 0; k < m->components; ++k)
    out[k] = 0.5f * h * (component_trilinear(s, m, k, c, qa) + component_trilinear(s, m, k, c, qb));
}

/* sums[k] += ∫ ρ_k along org + t dir over [0, len] in m; with target ≥ 0, stops where the
 * field Σ_k w_k ρ_k's integral reaches it: *t_hit that t (else -1). Returns the field's integral
 * up to where it stopped (0 without a target). */
inline float components_march(const SceneView* s, const __global KMedium* m, float3 org, float3 dir,
                              float len, const float* w, float target, float* sums, float* t_hit) {
  *t_hit = -1.0f;
  GridWalk g;
  if (!grid_walk_begin(m, org, dir, len, &g)) return 0.0f;
  float run = 0.0f, a, b, piece[KASHA_GRID_COMPONENTS];
  int3 c;
  while (grid_walk_next(&g, &c, &a, &b)) {
    components_cell_integrals(s, m, c, g.q0, g.dq, a, b, piece);
    if (target >= 0.0f) {
      float whole = 0.0f;
      for (int k = 0; k < m->components; ++k) whole += w[k] * piece[k];
      if (run + whole >= target && whole > 0.0f) {
        *t_hit = grid_cell_invert(s, m, w, c, g.q0, g.dq, a, b, whole, target - run);
        components_cell_integrals(s, m, c, g.q0, g.dq, a, *t_hit, piece);
        for (int k = 0; k < m->components; ++k) sums[k] += piece[k];
        return target;
      }
      run += whole;
    }
    for (int k = 0; k < m->components; ++k) sums[k] += piece[k];
  }
  return run;
}

/* The trail slot of component k of medium `index` (m its record): the medium's own for the first,
 * then its run of extra slots. */
inline int component_slot(const __global KMedium* m, int index, int k) {
  return k == 0 ? index : m->trail_extra + k - 1;
}

/* σt (then σs, N floats on) at x in the component grid m, per bin, into scratch slot `slot`. */
inline __global float* components_at(const SceneView* s, const __global KMedium* m, float3 x,
                                     int slot) {
  __global float* out = s->scratch + KASHA_SCRATCH_COMPONENTS + slot * 2 * KASHA_BINS;
  float3 q = grid_map(m, x, 1.0f), f = floor(q);
  int3 c = (int3)((int)f.x, (int)f.y, (int)f.z);
  for (int i = 0; i < 2 * KASHA_BINS; ++i) out[i] = 0.0f;
  for (int k = 0; k < m->components; ++k) {
    float rho = component_trilinear(s, m, k, c, q);
    if (!(rho > 0.0f)) continue;
    const __global float* st = s->spectra + m->sigma_t + k * KASHA_BINS;
    const __global float* ss = s->spectra + m->sigma_s + k * KASHA_BINS;
    for (int i = 0; i < KASHA_BINS; ++i) out[i] += rho * st[i], out[KASHA_BINS + i] += rho * ss[i];
  }
  return out;
}
#endif

#endif
