/* A medium's grid of density (docs/media.md#grid-media): σa, σs and its dyes' absorption times a
 * density given at the centres of nx × ny × nz cells over a box, trilinear between them and 0 past
 * the outermost samples' neighbours, as pbrt-v4's SampledGrid::Lookup; nothing outside the box.
 *
 * kasha tracks such a medium exactly instead of against a majorant: along a ray the density is,
 * within each cell of the sample lattice, a product of three linear functions of t — a cubic —
 * whose integral two-point Gauss–Legendre gives exactly. A segment's optical length ∫ density dt
 * then takes the place of its length (transmittance exp(−σt,i ∫ density), every bin at once), and
 * a free flight's collision is where bin j's optical depth σt,j ∫ density reaches the drawn one
 * (Newton's method inside the cell, kept in its bracket). Nothing is estimated, so every
 * transmittance, flight weight and MIS pseudo-density stays as it is for homogeneous media, and
 * the walks cost a lattice cell's two lookups per cell crossed. */
#ifndef KASHA_DENSITY_GRID_H
#define KASHA_DENSITY_GRID_H

#ifndef KASHA_MEDIUM_GRIDS
#define KASHA_MEDIUM_GRIDS 0
#endif
/* The most components a component grid of the scene has (colour_grid.h), 0: none. */
#ifndef KASHA_GRID_COMPONENTS
#define KASHA_GRID_COMPONENTS 0
#endif

#if KASHA_MEDIA && KASHA_MEDIUM_GRIDS
/* Sample (x, y, z) of the grid of m's lattice whose samples start at `base` in the spectra
 * buffer (its density, or an emitting grid's scale or temperature); 0 outside it. */
inline float grid_sample_in(const SceneView* s, const __global KMedium* m, int base, int x, int y, int z) {
  if (x < 0 || y < 0 || z < 0 || x >= m->grid_size[0] || y >= m->grid_size[1] || z >= m->grid_size[2]) return 0.0f;
  return s->spectra[base + (z * m->grid_size[1] + y) * m->grid_size[0] + x];
}

/* That grid's value at lattice point q inside the cell whose lowest corner is sample (x, y, z):
 * trilinear between its eight samples (q's offsets clamped to the cell). */
inline float grid_trilinear_in(const SceneView* s, const __global KMedium* m, int base, int x, int y, int z,
                               float3 q) {
  float3 d = clamp(q - (float3)((float)x, (float)y, (float)z), 0.0f, 1.0f);
  float c00 = mix(grid_sample_in(s, m, base, x, y, z), grid_sample_in(s, m, base, x + 1, y, z), d.x);
  float c10 = mix(grid_sample_in(s, m, base, x, y + 1, z), grid_sample_in(s, m, base, x + 1, y + 1, z), d.x);
  float c01 = mix(grid_sample_in(s, m, base, x, y, z + 1), grid_sample_in(s, m, base, x + 1, y, z + 1), d.x);
  float c11 = mix(grid_sample_in(s, m, base, x, y + 1, z + 1), grid_sample_in(s, m, base, x + 1, y + 1, z + 1), d.x);
  return mix(mix(c00, c10, d.y), mix(c01, c11, d.y), d.z);
}

/* The density there. */
inline float grid_trilinear(const SceneView* s, const __global KMedium* m, int x, int y, int z, float3 q) {
  return grid_trilinear_in(s, m, m->density, x, y, z, q);
}

/* The value at lattice point q of the grid at `base` (pbrt-v4's SampledGrid::Lookup). */
inline float grid_value_at(const SceneView* s, const __global KMedium* m, int base, float3 q) {
  float3 f = floor(q);
  return grid_trilinear_in(s, m, base, (int)f.x, (int)f.y, (int)f.z, q);
}

/* The density at lattice point q. */
inline float grid_density_at(const SceneView* s, const __global KMedium* m, float3 q) {
  return grid_value_at(s, m, m->density, q);
}

/* A world point's (w = 1) or direction's (w = 0) place in m's lattice. */
inline float3 grid_map(const __global KMedium* m, float3 p, float w) {
  const __global float* a = m->to_grid;
  return (float3)(a[0] * p.x + a[1] * p.y + a[2] * p.z + a[3] * w, a[4] * p.x + a[5] * p.y + a[6] * p.z + a[7] * w,
                  a[8] * p.x + a[9] * p.y + a[10] * p.z + a[11] * w);
}

#if KASHA_GRID_COMPONENTS
/* A component grid's component k (colour_grid.h) at lattice point q in cell c: 1 for the box-wide
 * one (the last, where m->uniform_last), else trilinear between the samples of its grid, the k-th
 * after m->density. */
inline float component_trilinear(const SceneView* s, const __global KMedium* m, int k, int3 c,
                                 float3 q) {
  if (m->uniform_last && k == m->components - 1) return 1.0f;
  int samples = m->grid_size[0] * m->grid_size[1] * m->grid_size[2];
  return grid_trilinear_in(s, m, m->density + k * samples, c.x, c.y, c.z, q);
}
#endif

/* The field a walk integrates, at lattice point q in cell c: the density, or (w non-null) a
 * component grid's Σ_k w_k ρ_k (colour_grid.h: a bin's σt). */
inline float grid_field(const SceneView* s, const __global KMedium* m, const float* w, int3 c,
                        float3 q) {
#if KASHA_GRID_COMPONENTS
  if (w) {
    float sum = 0.0f;
    for (int k = 0; k < m->components; ++k) sum += w[k] * component_trilinear(s, m, k, c, q);
    return sum;
  }
#endif
  return grid_trilinear(s, m, c.x, c.y, c.z, q);
}

/* ∫ of the field over t in [a, b] along q0 + t dq, inside the lattice cell c (a cubic: exact). */
inline float grid_cell_integral(const SceneView* s, const __global KMedium* m, const float* w,
                                int3 c, float3 q0, float3 dq, float a, float b) {
  const float k = 0.28867513f; /* 1 / (2√3) */
  float h = b - a, mid = 0.5f * (a + b);
  return 0.5f * h *
         (grid_field(s, m, w, c, q0 + (mid - k * h) * dq) +
          grid_field(s, m, w, c, q0 + (mid + k * h) * dq));
}

/* Where in [a, b] (cell c, holding `whole` of the integral) the field's integral from a reaches r:
 * Newton's method kept in its bracket, bisection where it would leave it. */
inline float grid_cell_invert(const SceneView* s, const __global KMedium* m, const float* w, int3 c,
                              float3 q0, float3 dq, float a, float b, float whole, float r) {
  float lo = a, hi = b, t = a + (b - a) * fmin(r / whole, 1.0f);
  for (int k = 0; k < 12; ++k) {
    float excess = grid_cell_integral(s, m, w, c, q0, dq, a, t) - r;
    if (excess == 0.0f) return t;
    if (excess > 0.0f) hi = t;
    else lo = t;
    float rate = grid_field(s, m, w, c, q0 + t * dq);
    float next = rate > 0.0f ? t - excess / rate : 0.5f * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5f * (lo + hi);
    if (fabs(next - t) <= 1e-6f * (b - a)) return next;
    t = next;
  }
  return t;
}

/* The ray's span within the lattice's box [-½, n − ½]³ (as t along q0 + t dq), clipped to [0, len];
 * false if it misses (or the map gave a non-finite point). */
inline bool grid_span(const __global KMedium* m, float3 q0, float3 dq, float len, float* t0, float* t1) {
  if (!(isfinite(q0.x) && isfinite(q0.y) && isfinite(q0.z) && isfinite(dq.x) && isfinite(dq.y) && isfinite(dq.z)))
    return false;
  float3 n = (float3)((float)m->grid_size[0], (float)m->grid_size[1], (float)m->grid_size[2]);
  float3 lo = ((float3)(-0.5f) - q0) / dq, hi = (n - 0.5f - q0) / dq;
  float3 near_t = fmin(lo, hi), far_t = fmax(lo, hi);
  /* An axis the ray runs parallel to: inside its slab for all t, or never. */
  if (dq.x == 0.0f) near_t.x = -INFINITY, far_t.x = (q0.x >= -0.5f && q0.x <= n.x - 0.5f) ? INFINITY : -INFINITY;
  if (dq.y == 0.0f) near_t.y = -INFINITY, far_t.y = (q0.y >= -0.5f && q0.y <= n.y - 0.5f) ? INFINITY : -INFINITY;
  if (dq.z == 0.0f) near_t.z = -INFINITY, far_t.z = (q0.z >= -0.5f && q0.z <= n.z - 0.5f) ? INFINITY : -INFINITY;
  *t0 = fmax(fmax(fmax(near_t.x, near_t.y), near_t.z), 0.0f);
  *t1 = fmin(fmin(fmin(far_t.x, far_t.y), far_t.z), len);
  return *t0 < *t1;
}

/* One axis of the cell walk: the cell's index along it, the t of the plane the ray leaves it by
 * and the t between planes (Amanatides and Woo); INFINITY where the ray runs parallel. */
inline void grid_axis(float q0, float dq, float q, int* cell, float* next, float* step) {
  *cell = (int)floor(q);
  *next = dq > 0.0f ? ((float)*cell + 1.0f - q0) / dq : dq < 0.0f ? ((float)*cell - q0) / dq : INFINITY;
  *step = dq != 0.0f ? 1.0f / fabs(dq) : INFINITY;
}

/* A ray's walk through the lattice's cells, piece by piece (every piece lies in one cell): the
 * ray in lattice space, the cell, the t of the planes it leaves by along each axis and between
 * them, and the t it has reached of the span's end. */
typedef struct {
  float3 q0, dq;
  int3 cell, unit;
  float3 next, step;
  float t, end;
  int left; /* pieces it may still take: a guard against a walk that does not advance */
} GridWalk;

/* The walk of org + t dir, t in [0, len], through m's lattice; false if it misses the box. */
inline bool grid_walk_begin(const __global KMedium* m, float3 org, float3 dir, float len,
                            GridWalk* g) {
  g->q0 = grid_map(m, org, 1.0f);
  g->dq = grid_map(m, dir, 0.0f);
  if (!grid_span(m, g->q0, g->dq, len, &g->t, &g->end)) return false;
  /* The first cell: where the span's first sliver lies. */
  float3 q = g->q0 + fmin(g->t + 1e-4f * (g->end - g->t), 0.5f * (g->t + g->end)) * g->dq;
  int cx, cy, cz;
  float nx, ny, nz, sx, sy, sz;
  grid_axis(g->q0.x, g->dq.x, q.x, &cx, &nx, &sx);
  grid_axis(g->q0.y, g->dq.y, q.y, &cy, &ny, &sy);
  grid_axis(g->q0.z, g->dq.z, q.z, &cz, &nz, &sz);
  g->cell = (int3)(cx, cy, cz);
  g->next = (float3)(nx, ny, nz);
  g->step = (float3)(sx, sy, sz);
  g->unit = (int3)(g->dq.x > 0.0f ? 1 : -1, g->dq.y > 0.0f ? 1 : -1, g->dq.z > 0.0f ? 1 : -1);
  g->left = m->grid_size[0] + m->grid_size[1] + m->grid_size[2] + 6;
  return true;
}

/* The walk's next piece: its cell *c and its span [*a, *b]; false when the walk is over. */
inline bool grid_walk_next(GridWalk* g, int3* c, float* a, float* b) {
  if (g->left-- <= 0 || !(g->t < g->end)) return false;
  *c = g->cell;
  *a = g->t;
  *b = fmax(fmin(fmin(fmin(g->next.x, g->next.y), g->next.z), g->end), g->t);
  g->t = *b;
  /* Into the neighbour across the plane it leaves by. */
  if (g->next.x <= g->next.y && g->next.x <= g->next.z)
    g->cell.x += g->unit.x, g->next.x += g->step.x;
  else if (g->next.y <= g->next.z)
    g->cell.y += g->unit.y, g->next.y += g->step.y;
  else
    g->cell.z += g->unit.z, g->next.z += g->step.z;
  return true;
}

/* ∫ density along org + t dir over [0, len] in m, cell by cell; with target ≥ 0, stops where the
 * integral reaches it: *t_hit that t (else -1). Returns the integral up to where it stopped. */
inline float grid_march(const SceneView* s, const __global KMedium* m, float3 org, float3 dir,
                        float len, float target, float* t_hit) {
  *t_hit = -1.0f;
  GridWalk g;
  if (!grid_walk_begin(m, org, dir, len, &g)) return 0.0f;
  float sum = 0.0f, a, b;
  int3 c;
  while (grid_walk_next(&g, &c, &a, &b)) {
    float piece = grid_cell_integral(s, m, 0, c, g.q0, g.dq, a, b);
    if (target >= 0.0f && sum + piece >= target && piece > 0.0f) {
      *t_hit = grid_cell_invert(s, m, 0, c, g.q0, g.dq, a, b, piece, target - sum);
      return target;
    }
    sum += piece;
  }
  return sum;
}
#endif

#endif
