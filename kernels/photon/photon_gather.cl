/* Photon mapping's gather on the device (included by photon_map.cl): the hashed grid's cell size
 * from the visible points' radii (the grid itself: hash_grid.cl), the gather at each pixel's
 * visible point through it, and the per-pixel SPPM statistics (sppm_statistics.h) kept here
 * between passes.
 * Only disc_coverage, which traces rays, takes the scene's and the film's parameters; the others
 * take their own arguments alone (KernelIntegrator::launch_own). */

#include "transport/disc_coverage.h"
#include "transport/sphere_coverage.h"
#include "transport/hash_grid.cl"
#include "photon/sppm_statistics.h"
#include "shared/volume_gather.h"

/* One work-group: the grid's cell size from the radii of this pass's visible points — twice their
 * mean, but at least a quarter of the largest, so a gather visits at most 9³ cells and a typical
 * one 2³. cell[0] = size, cell[1] = 1/size. */
__kernel void grid_cell_size(__global const float* visible_points, __global const float* radius, int pixels,
                             __global float* cell, KASHA_LAUNCH_RANGE) {
  __local float sum[256], most[256];
  __local int valid[256];
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE, KASHA_SCATTERING);
  int l = get_local_id(0), n = min((int)get_local_size(0), 256);
  float s = 0.0f, m = 0.0f;
  int v = 0;
  if (l < n)
    for (int p = l; p < pixels; p += n)
      if (visible_points[(long)p * vp_floats + KASHA_VP_VALID] != 0.0f) {
        s += radius[p];
        m = fmax(m, radius[p]);
        ++v;
      }
  if (l < n) sum[l] = s, most[l] = m, valid[l] = v;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (l == 0) {
    for (int i = 1; i < n; ++i) s += sum[i], m = fmax(m, most[i]), v += valid[i];
    float size = v > 0 ? fmax(2.0f * s / v, 0.25f * m) : 1.0f;
    if (!(size > 0.0f)) size = 1.0f;
    cell[0] = size;
    cell[1] = 1.0f / size;
  }
}

/* Whether the visible point vp on a surface (at x, normal n) gathers the photon ph at y, within
 * its radius r: on the same side of the surface, roughly the same orientation, and near the
 * tangent plane (no leaks through thin walls, around corners or from a parallel surface just
 * behind). A photon in a medium has no normal and never faces it. */
inline bool surface_gathers(const __global float* vp, float3 n, const __global float* ph, float3 x, float3 y, float r) {
  float facing = ph[3] * vp[3] + ph[4] * vp[4];
  if (facing + ph[5] * vp[5] < 0.5f) return false;
  float off = (y.x - x.x) * n.x + (y.y - x.y) * n.y;
  off = off + (y.z - x.z) * n.z;
  return !(fabs(off) > KASHA_GATHER_SLAB * r);
}

/* Per pixel: adds Σ K·Φ over the batch's photons within its radius — at a surface those
 * surface_gathers takes, in a medium the medium's photons with their phase function
 * (volume_gather.h) — to pass_flux, and their number to pass_found. A photon is counted only from
 * its own cell, which other cells may share a hash with. */
__kernel void gather_photons(__global const float* cmf, /* the film's C (film_view.h) */
                             __global const float* visible_points, __global const float* radius,
                             __global const float* store, __global const int* sorted,
                             __global const int* cell_count, __global const int* cell_end,
                             __global const float* cell, uint mask, __global float* pass_flux,
                             __global int* pass_found, KASHA_LAUNCH_RANGE) {
  int pixel = launch_item(item_first);
  if (pixel >= item_end) return;
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE, KASHA_SCATTERING);
  const __global float* vp = visible_points + (long)pixel * vp_floats;
  if (vp[KASHA_VP_VALID] == 0.0f) return;
  const float r = radius[pixel], r2 = r * r, inv_cell = cell[1];
  float3 x = record_position(vp), n = (float3)(vp[3], vp[4], vp[5]);
#if KASHA_SCATTERING
  const bool in_medium = record_in_medium(vp);
#endif
  int3 lo = grid_cell(x - r, inv_cell), hi = grid_cell(x + r, inv_cell);
  VertexFactorLayout layout = {KASHA_BINS, KASHA_FILM_ROWS, KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE, cmf};
  kasha_real rows[KASHA_FILM_ROWS];
  for (int k = 0; k < KASHA_FILM_ROWS; ++k) rows[k] = 0;
  int found = 0;
  for (int cz = lo.z; cz <= hi.z; ++cz)
    for (int cy = lo.y; cy <= hi.y; ++cy)
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        int3 c = (int3)(cx, cy, cz);
        uint h = grid_hash(c, mask);
        int end = cell_end[h];
        for (int j = end - cell_count[h]; j < end; ++j) {
          const __global float* ph = store + (long)sorted[j] * KASHA_RECORD_FLOATS;
          float3 y = record_position(ph);
          int3 own = grid_cell(y, inv_cell);
          if (own.x != cx || own.y != cy || own.z != cz) continue;
          float dx = x.x - y.x, dy = x.y - y.y, dz = x.z - y.z;
          float d2 = dx * dx + dy * dy;
          d2 = d2 + dz * dz;
          if (!(d2 < r2)) continue;
          kasha_real scale = 1;
#if KASHA_SCATTERING
          if (in_medium) {
            if (!record_in_medium(ph)) continue;
            scale = volume_gather_weight(vp, ph, KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE, r);
          } else if (!surface_gathers(vp, n, ph, x, y, r)) {
            continue;
          }
#else
          if (!surface_gathers(vp, n, ph, x, y, r)) continue;
#endif
#ifdef KASHA_DEPTH_CAP
          /* The camera's bounces, the photon's and the merged vertex: at most the cap. */
          if ((int)vp[KASHA_VP_VALID] - 1 + as_int(ph[KASHA_PHOTON_DEPTH]) + 1 > KASHA_DEPTH_CAP) continue;
#endif
          ++found;
          vf_apply_scaled(layout, vp, ph + KASHA_PHOTON_POWER, scale, rows);
        }
      }
  __global float* out = pass_flux + (long)pixel * KASHA_FILM_ROWS;
  for (int k = 0; k < KASHA_FILM_ROWS; ++k) out[k] += (float)rows[k];
  pass_found[pixel] += found;
}

/* Edge correction (disc_coverage.h): per pixel with a visible point, `probes` probes of its disc
 * (of its sphere in a medium, sphere_coverage.h) on a pattern rotated by `rotation`; the fraction covered and the number of passes measured go to
 * coverage[2·pixel], coverage[2·pixel + 1]. The image divides by their ratio once (a ratio of
 * sums: a per-pass division would be a mean of noisy ratios, biased high). */
__kernel void disc_coverage(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, __global const float* visible_points,
                            __global const float* radius, __global float* coverage, int probes, float rotation,
                            KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  int pixel = launch_item(item_first);
  if (pixel >= item_end) return;
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE, KASHA_SCATTERING);
  const __global float* vp = visible_points + (long)pixel * vp_floats;
  if (vp[KASHA_VP_VALID] == 0.0f) return;
  const float r = radius[pixel];
  float3 x = record_position(vp), n = (float3)(vp[3], vp[4], vp[5]);
#if KASHA_SCATTERING
  if (record_in_medium(vp)) {
    coverage[2 * pixel] += sphere_covered(&s, x, r, probes, rotation);
    coverage[2 * pixel + 1] += 1.0f;
    add_ray_counts(&s, ray_counts);
    return;
  }
#endif
  coverage[2 * pixel] += disc_covered(&s, x, n, r, KASHA_GATHER_SLAB * r, probes, rotation);
  coverage[2 * pixel + 1] += 1.0f;
  add_ray_counts(&s, ray_counts);
}

/* Per pixel: the pass's gather (its flux scaled by `scale`, 1/the fraction of the pass's photons
 * traced) into the SPPM statistics; clears the pass's sums for the next. */
__kernel void sppm_update(__global float* radius, __global float* count, __global float* tau,
                          __global float* pass_flux, __global int* pass_found, float alpha, float scale,
                          KASHA_LAUNCH_RANGE) {
  int pixel = launch_item(item_first);
  if (pixel >= item_end) return;
  __global float* phi = pass_flux + (long)pixel * KASHA_FILM_ROWS;
  sppm_add_pass(radius + pixel, count + pixel, tau + (long)pixel * KASHA_FILM_ROWS, KASHA_FILM_ROWS, phi, scale,
                pass_found[pixel], alpha);
  pass_found[pixel] = 0;
  for (int k = 0; k < KASHA_FILM_ROWS; ++k) phi[k] = 0.0f;
}

/* Per pixel: the image so far — the mean of the camera samples' direct estimates over `passes`
 * passes plus the SPPM radiance. */
__kernel void sppm_image(float bin_nm, /* the scene's bin width (KASHA_SCENE_PARAMS' bin_nm) */
                         __global const float* direct, __global const float* radius, __global const float* tau,
                         __global const float* coverage, int edge_correction, float passes,
                         __global float* image, KASHA_LAUNCH_RANGE) {
  int pixel = launch_item(item_first);
  if (pixel >= item_end) return;
  float covered = 1.0f;
  if (edge_correction && coverage[2 * pixel] > 0.0f) covered = coverage[2 * pixel] / coverage[2 * pixel + 1];
  for (int k = 0; k < KASHA_FILM_ROWS; ++k) {
    long i = (long)pixel * KASHA_FILM_ROWS + k;
    image[i] = (passes > 0.0f ? direct[i] / passes : 0.0f) +
               sppm_radiance(radius[pixel], tau + (long)pixel * KASHA_FILM_ROWS, k, passes, bin_nm) / covered;
  }
}
