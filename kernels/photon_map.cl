/* Bidirectional photon mapping (DESIGN §2.3), the two device passes; the gather runs on the host.
 * Camera paths through gloss bounces end by Russian roulette (roulette.h), as backward's.
 * Photon pass: photons as in forward transport, stored at every hit with a Lambert part (before
 * they scatter); gloss bounces are followed, not stored. Camera pass: one path per pixel through
 * gloss bounces to the first vertex with a Lambert part, where it stores a visible point with the
 * compact factor K (vertex_factor.h); emission seen along the way goes straight to the pixel. */
#include "camera.h"
#include "branch_choice.h"
#include "film_view.h"
#include "hit_point.h"
#include "photon_layout.h"
#include "photon_transport.h"
#include "scene_view.h"
#include "vertex_factor.h"

#include "roulette.h"

/* Photons [first_photon, first_photon + count) of the pass's `photons`, `photons_per_item` per work
 * item, stored from slot *stored on; a store past `capacity` is counted but not written, so the
 * host sees the overflow and traces the launch again into an emptier store. A photon that alone
 * stores more than the store holds is traced again in segments: `skip` of its stores are passed
 * over (launches of one photon only). */
__kernel void trace_photon_map(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, int photons, int first_photon, int count,
                               int photons_per_item, int skip, __global float* store, __global int* stored,
                               int capacity,
                               __global float* cut, /* per item: power the depth guard cut, per photon's start */
                               uint seed, uint pass,
                  int item_end /* launches are rounded up to whole work-groups */) {
  KASHA_SCENE_VIEW(s);
  int item = get_global_id(0);
  if (item >= item_end) return;
  int first = first_photon + item * photons_per_item;
  int last = min(first + photons_per_item, first_photon + count);
  float guard = 0.0f;
  for (int index = first; index < last; ++index) {
    Sampler sampler = photon_sampler(seed, pass, photons, index);
    LightOrigin o;
    Photon p = emit_photon(&s, (float)photons, &sampler, &o);
    p.position += o.normal * o.eps;
    int skip_left = skip;
    for (int depth = 0;; ++depth) {
      if (depth == KASHA_MAX_PATH_DEPTH) {
        guard += photon_total(&p) / p.start;
        break;
      }
      HitPoint h;
      if (!intersect_scene(&s, p.position, p.direction, &h)) break;
      float3 ns = h.ns, x = h.x;
      Surface surf;
      load_surface(&s, h.material, &surf);
      if (surface_has_lambert(&surf)) {
        if (skip_left > 0) {
          --skip_left;
        } else {
          int slot = atomic_inc(stored);
          if (slot < capacity) {
            __global float* rec = store + (long)slot * KASHA_PHOTON_FLOATS(KASHA_BINS);
            rec[0] = x.x, rec[1] = x.y, rec[2] = x.z;
            rec[3] = ns.x, rec[4] = ns.y, rec[5] = ns.z;
            for (int i = 0; i < KASHA_BINS; ++i) rec[KASHA_PHOTON_POWER + i] = p.power[i];
          }
        }
      }
      if (scatter_photon(&p, &surf, &s, x, ns, h.eps, &sampler, depth) == BRANCH_ABSORBED) break;
    }
  }
  if (first < last) cut[item] = guard;
}

__kernel void camera_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, __global float* visible_points,
                          __global float* direct, /* pixels × KASHA_FILM_ROWS: emission seen directly */
                          __global float* cut,    /* per pixel: weight the depth guard cut */
                          uint seed, uint pass,
                  int item_end /* launches are rounded up to whole work-groups */) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int pixel = get_global_id(0);
  if (pixel >= item_end) return;
  if (pixel >= camera.width * camera.height) return;
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE);
  __global float* vp = visible_points + (long)pixel * vp_floats;
  vp[KASHA_VP_VALID] = 0.0f;
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  /* The pixel's stream (one sample per pass); a seed apart from the photons'. */
  Sampler sampler = sampler_start(seed ^ 0x5bd1e995u, (uint)pixel, pass, pass, (uint)pixel);
  float3 org = camera_position(&camera);
  float3 dir = camera_sample(&camera, pixel, sample_2d(&sampler));
  PathWeight p; /* diagonal mode only: the path goes through gloss bounces alone */
  pw_init(&p, &f);
  const float start = pw_magnitude(&p, &f);
  float travelled = 0.0f;
  cut[pixel] = 0.0f;

  for (int depth = 0;; ++depth) {
    if (depth == KASHA_MAX_PATH_DEPTH) {
      cut[pixel] = pw_magnitude(&p, &f) / start;
      break;
    }
    HitPoint h;
    if (!intersect_scene(&s, org, dir, &h)) break;
    travelled += h.t;
    float3 wo = -dir, ns = h.ns, x = h.x;
    if (h.emitter >= 0 && h.front) pw_add(&p, &f, emitter_spectrum(&s, h.emitter), 0, 1.0f, rows);
    Surface surf;
    load_surface(&s, h.material, &surf);
    /* Gloss or the Lambert parts, by their energies under equal-energy light (as backward). */
    float3 probs = branch_probabilities(&p, &f, &surf);
    float p_gloss = probs.x;
    bool lambert = probs.y + probs.z > 0.0f;
    sampler_at(&sampler, 1 + 3 * depth); /* per vertex: (choice, lobe azimuth), direction, roulette */
    float2 u_choice = sample_2d(&sampler), u_dir = sample_2d(&sampler), u_roulette = sample_2d(&sampler);
    if (lambert && u_choice.x >= p_gloss) {
      /* The visible point, K over 1 − P_gloss. */
      vp[0] = x.x, vp[1] = x.y, vp[2] = x.z;
      vp[3] = ns.x, vp[4] = ns.y, vp[5] = ns.z;
      vp[KASHA_VP_VALID] = 1.0f;
      vp[KASHA_VP_DISTANCE] = travelled;
      VertexFactorLayout layout = {KASHA_BINS, KASHA_FILM_ROWS, KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE, cmf};
#if KASHA_FLUORESCENCE
      vf_build(layout, vp, p.w, surf.rho, surf.ehat, surf.a, KASHA_INV_PI / (1.0f - p_gloss));
#else
      vf_build(layout, vp, p.w, surf.rho, 0, 0, KASHA_INV_PI / (1.0f - p_gloss));
#endif
      break;
    }
    if (p_gloss <= 0.0f) break;
    float3 mirror = reflect_dir(dir, ns);
    float weight = surf.g / p_gloss;
    if (surf.mirror) {
      dir = mirror;
    } else {
      float pdf;
      float3 wi = sample_lobe(surf.m, lobes, mirror, u_dir.x, u_dir.y, u_choice.y, &pdf);
      float ci = dot(wi, ns), co = dot(wo, ns);
      if (ci <= 0.0f) break;
      weight *= 2.0f * ci / (ci + co);
      dir = wi;
    }
    pw_scatter_diagonal(&p, 0, weight);
    if (depth >= KASHA_CAMERA_ROULETTE_FROM) {
      float keep = roulette(pw_magnitude(&p, &f) / start, u_roulette.x);
      if (keep == 0.0f) break;
      if (keep != 1.0f) pw_scatter_diagonal(&p, 0, keep);
    }
    org = x + ns * h.eps;
  }
  film_add(direct, pixel, rows);
}
