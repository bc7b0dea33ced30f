/* Vertex connection and merging (docs/integrators.md#vertex-connection-and-merging): Georgiev,
 * Křivánek, Davidovič and Slusallek 2012, as SmallVCM's vertexcm.hxx lays it out, with kasha's
 * transport — light subpaths are spectral photons (photon_transport.h: fluorescent re-emission,
 * constant-energy branching), camera subpaths carry a diagonal or rank-1 colour (path_weight.h),
 * so a connection T·f·G·f·Φ and a merge T·f·Φ cost O(N) and never pair wavelengths.
 *
 * An iteration is two launches and a grid:
 * 1. vcm_light_pass: light subpaths (one per pixel, 32 in a caustic-lit view; ppm at least
 *    2^16); each vertex with a non-delta part is stored (vcm_records.h), linked to its path's
 *    previous one, and (connecting modes) splatted to the camera, MIS-weighted — the light point
 *    it leaves from too, against the camera's direct hit of it;
 * 2. the hashed grid over the stored vertices (hash_grid.cl; merging modes), cells of 2r;
 * 3. vcm_camera_pass: one camera path per pixel; at each vertex with a non-delta part, emission
 *    hit, next-event estimation, connections to its light subpath's vertices (connecting modes)
 *    and merges with the stored vertices within r (merging modes), each MIS-weighted; where the
 *    light seen through delta bounces alone has an edge, that light from extra samples
 *    (vcm_seen_light).
 * Modes are build options: KASHA_VCM_CONNECT and KASHA_VCM_MERGE both (vcm), connections only
 * (bpt), merges only (ppm: unweighted, once at the camera path's first non-delta vertex).
 *
 * MIS is the balance heuristic through Georgiev's recursive partial weights dVCM, dVC, dVM, each
 * subpath's kept from its start (SmallVCM's names). Kasha chooses branches by the path's
 * spectrum, which the other subpath cannot know; the weights use pseudo-densities both sides
 * evaluate alike from the geometry and the material alone (vcm_pdf: the gloss share from the
 * material, a light point by area), so every path's weights still sum to one, while each
 * contribution divides by the density it was truly sampled with — unbiased for connections, as
 * consistent as photon mapping for merges.
 *
 * Read in this order (SmallVCM's seams, one header each): vcm_records.h (what the host and the
 * kernels share), vcm_modes.h (modes, test hooks, the MIS factors), vcm_pdf.h and vcm_eval.h
 * (pseudo-densities and f at a vertex), vcm_weights.h (the partial weights' recursion), vcm_media.h
 * (collisions in scattering media as vertices),
 * vcm_light_path.h (the light pass), vcm_camera.h (a camera subpath's state), then its
 * techniques — vcm_emission.h, vcm_next_event.h, vcm_connect.h, vcm_merge.h, vcm_seen_light.h —
 * and vcm_camera_path.h, which takes them in turn; the two kernels below. */
#include "shared/vcm_records.h"

/* The store's stride, and (hash_grid.cl) the grid holds only the vertices merges may use. */
#define VCM_FLOATS KASHA_VCM_VERTEX_FLOATS(KASHA_BINS)
#define KASHA_RECORD_FLOATS VCM_FLOATS
#define KASHA_RECORD_IN_GRID(r) (((const __global KVcmLightVertex*)(r))->flags & KASHA_VCM_MERGEABLE)

/* Included before the vcm headers: hash_grid.cl turns floating-point contraction off for all
 * that follows it (its gather must round as the host's does), vcm's code included. */
#include "geometry/camera.h"
#include "film/camera_splat.h"
#include "transport/camera_walk.h"
#include "transport/disc_coverage.h"
#include "transport/hash_grid.cl"
#include "transport/photon_transport.h"
#include "transport/photon_medium.h"

#include "vcm/vcm_modes.h"
#include "vcm/vcm_pdf.h"
#include "vcm/vcm_eval.h"
#include "vcm/vcm_weights.h"
#include "vcm/vcm_media.h"
#include "vcm/vcm_light_path.h"
#include "vcm/vcm_camera.h"
#include "vcm/vcm_emission.h"
#include "vcm/vcm_next_event.h"
#include "vcm/vcm_connect.h"
#include "vcm/vcm_merge.h"
#include "vcm/vcm_seen_light.h"
#include "vcm/vcm_camera_path.h"

/* Light subpath launch_item(item_first) of the iteration's `paths` (the launches cover the
 * store's chunk [chunk_first, chunk_end)), traced into the store (vcm_light_path); its last
 * stored vertex and its depth-guard tally go to its place in the chunk's `light_paths`. */
__kernel void vcm_light_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, KVcmIteration it, __global float* store,
                             __global KVcmCounters* counters, __global KVcmLightPath* light_paths,
                             __global ulong* film, __global const KVcmPixel* pixels, KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int index = launch_item(item_first);
  if (index >= item_end) return;
  SplatTarget target = {film, it.film_shift, 0};
  __global KVcmLightPath* path = &light_paths[index - it.chunk_first];
  path->cut = vcm_light_path(&s, &f, &it, index, store, counters, &target, pixels, &path->last);
  if (target.overflow) atomic_add(&counters->overflow, target.overflow);
  add_ray_counts(&s, ray_counts);
}

/* The hashed grid's buffers (hash_grid.cl), in the modes that merge. */
#if KASHA_VCM_MERGE
#define VCM_GRID_PARAMS , __global const float4 *placed, __global const int *cell_end
#define VCM_GRID_VIEW(name) const VcmGrid name = {placed, cell_end}
#else
#define VCM_GRID_PARAMS
#define VCM_GRID_VIEW(name) const VcmGrid name = {0}
#endif

/* `spp` camera paths a pixel, sample j's light subpath (pixel · spp + j) modulo `paths`, their
 * estimates with the store's chunk of light subpaths [chunk_first, chunk_end) added to the pixel's
 * sums: the same paths (the same random numbers) with every chunk. `path_spectra`: VCM_SPECTRA
 * floats per work item for a light vertex's f·Φ and surface. */
__kernel void vcm_camera_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, KVcmIteration it, __global const float* store,
                              __global const KVcmLightPath* light_paths VCM_GRID_PARAMS,
                              __global float* path_spectra, __global float* sums, __global KVcmPixel* pixels,
                              KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  VCM_GRID_VIEW(grid);
  int pixel = launch_pixel(&s.camera, item_first, item_end);
  if (pixel < 0) return;
  const int spp = it.spp;
  const uint pass = it.pass;
  /* The pixel's stream: a seed apart from the light subpaths'. */
  Sampler sampler = sampler_start(it.seed ^ 0x5bd1e995u, (uint)pixel, 0, pass, (uint)pixel);
  __global float* out = path_spectra + (long)get_global_id(0) * VCM_SPECTRA;
  float guard = 0.0f;
  int bad = 0;
  bool owned = false;
  /* The light seen through delta bounces alone, in the pixels the host found it in
   * (KVcmPixel.seen), from `seen_samples` samples per camera path, each index of their own stream
   * a point of one Sobol sequence; elsewhere the camera paths take it. */
  int seen = pixels[pixel].seen ? it.seen_samples : 0;
  Sampler seen_sampler = sampler_start(it.seed ^ 0x7f4a7c15u, (uint)pixel, 0, pass, (uint)pixel);
  for (int j = 0; j < spp; ++j) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)j);
    float rows[KASHA_FILM_ROWS];
    film_rows_clear(rows);
    int partner = (int)(((long)pixel * spp + j) % it.paths);
    bool own = partner >= it.chunk_first && partner < it.chunk_end;
    const VcmCameraInputs in = {&it, store, light_paths, &grid, out, partner, own, seen > 0};
    float g = vcm_camera_path(&s, &f, pixel, &sampler, &in, rows);
    if (own && seen > 0) {
      float seen_rows[KASHA_FILM_ROWS], seen_cut = 0.0f;
      film_rows_clear(seen_rows);
      for (int k = 0; k < seen; ++k) {
        sampler_next_sample(&seen_sampler, (pass * (uint)spp + (uint)j) * (uint)seen + (uint)k);
        seen_cut += vcm_seen_light(&s, &f, &it, seen, pixel, &seen_sampler, seen_rows);
      }
      for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += seen_rows[r] / (float)seen;
      guard += seen_cut / (float)seen; /* the depth guard's tally: a camera path's share */
    }
    if (own) guard += g, owned = true;
    if (film_rows_finite(rows))
      film_add(sums, pixel, rows);
    else
      ++bad;
  }
  if (owned) pixels[pixel].cut += guard;
  pixels[pixel].rejected += bad;
  add_ray_counts(&s, ray_counts);
}
