/* Bidirectional photon mapping (DESIGN §2.3), the two device passes; the gather runs on the host.
 * Photon pass: photons as in forward transport, stored at every hit with a Lambert part (before
 * they scatter); gloss bounces are followed, not stored. Camera pass: one path per pixel through
 * gloss bounces to the first vertex with a Lambert part, where it stores a visible point with the
 * compact factor K; emission seen along the way goes straight to the pixel. */
#include "bvh_traversal.h"
#include "camera.h"
#include "film_rows.h"
#include "hit_point.h"
#include "photon_layout.h"
#include "photon_transport.h"
#include "scene_params.h"

#define PHOTON_MAX_DEPTH 1000
#define CAMERA_MAX_DEPTH 64

__kernel void trace_photon_map(KASHA_SCENE_PARAMS, float bin_nm, float ray_eps,
                               int photons, int photons_per_item, __global float* store, __global int* stored,
                               int capacity, uint seed, uint pass) {
  int item = get_global_id(0);
  int first = item * photons_per_item, last = min(first + photons_per_item, photons);
  for (int index = first; index < last; ++index) {
    Rng rng = rng_seed(seed, pass, (uint)index);
    LightOrigin o;
    Photon p = emit_photon(tris, light_tri, light_cdf, light_count, emitter_radiance, emitter_area_pdf, bin_nm,
                           (float)photons, &rng, &o);
    p.position += o.normal * ray_eps;
    for (int depth = 0; depth < PHOTON_MAX_DEPTH; ++depth) {
      HitPoint h;
      if (!intersect_scene(nodes, tris, p.position, p.direction, &h)) break;
      float3 ns = h.ns, x = h.x;
      const __global KMaterial* m = &materials[h.material];
      Surface s;
      load_surface(m, spectra, &s);
      if (surface_has_lambert(&s)) {
        int slot = atomic_inc(stored);
        if (slot < capacity) {
          __global float* rec = store + (long)slot * KASHA_PHOTON_FLOATS(KASHA_BINS);
          rec[0] = x.x, rec[1] = x.y, rec[2] = x.z;
          rec[3] = ns.x, rec[4] = ns.y, rec[5] = ns.z;
          for (int i = 0; i < KASHA_BINS; ++i) rec[KASHA_PHOTON_POWER + i] = p.power[i];
        }
      }
      if (scatter_photon(&p, &s, m, lobes, x, ns, ray_eps, &rng) == BRANCH_ABSORBED) break;
    }
  }
}

__kernel void camera_pass(KCamera camera, KASHA_SCENE_PARAMS,
                          __global const float* cmf, __global const float* importance, float ray_eps,
                          __global float* visible_points, __global float* direct, uint seed, uint pass) {
  int pixel = get_global_id(0);
  if (pixel >= camera.width * camera.height) return;
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE);
  __global float* vp = visible_points + (long)pixel * vp_floats;
  vp[KASHA_VP_VALID] = 0.0f;
  float rows[KASHA_FILM_ROWS];
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] = 0.0f;
  /* A seed stream apart from the photons' (whose items count photons, not pixels). */
  Rng rng = rng_seed(seed ^ 0x5bd1e995u, pass, (uint)pixel);
  int px = pixel % camera.width, py = pixel / camera.width;
  float3 org = camera_position(&camera);
  float3 dir = camera_direction(&camera, px + rng_next_float(&rng), py + rng_next_float(&rng));
  float w[KASHA_BINS];
  for (int i = 0; i < KASHA_BINS; ++i) w[i] = 1.0f;
  float travelled = 0.0f;

  for (int depth = 0; depth < CAMERA_MAX_DEPTH; ++depth) {
    HitPoint h;
    if (!intersect_scene(nodes, tris, org, dir, &h)) break;
    travelled += h.t;
    float3 wo = -dir, ns = h.ns, x = h.x;
    if (h.emitter >= 0 && h.front) {
      const __global float* le = emitter_radiance + h.emitter * KASHA_BINS;
#if KASHA_SPECTRAL_FILM
      for (int i = 0; i < KASHA_BINS; ++i) rows[i] += w[i] * le[i];
#else
      for (int r = 0; r < 3; ++r)
        for (int i = 0; i < KASHA_BINS; ++i) rows[r] += cmf[r * KASHA_BINS + i] * w[i] * le[i];
#endif
    }
    const __global KMaterial* m = &materials[h.material];
    Surface s;
    load_surface(m, spectra, &s);
    /* Gloss or the Lambert parts, by their energies under equal-energy light (as backward). */
    float w0 = 0.0f, wl = 0.0f, we = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) {
      w0 += importance[i] * w[i];
      wl += importance[i] * w[i] * s.rho[i];
#if KASHA_FLUORESCENCE
      we += importance[i] * w[i] * s.ehat[i];
#endif
    }
#if KASHA_FLUORESCENCE
    wl += we * s.a_sum;
#endif
    bool lambert = surface_has_lambert(&s) && wl > 0.0f;
    float wg = s.g * w0;
    float p_gloss = lambert ? wg / (wg + wl) : (s.g > 0.0f ? 1.0f : 0.0f);
    if (lambert && rng_next_float(&rng) >= p_gloss) {
      /* The visible point: K = C∘d + c bᵀ, d = w∘ρ/π, c = C·(w∘ê)/π, b = a, over 1 − P_gloss. */
      float k = KASHA_INV_PI / (1.0f - p_gloss);
      vp[0] = x.x, vp[1] = x.y, vp[2] = x.z;
      vp[3] = ns.x, vp[4] = ns.y, vp[5] = ns.z;
      vp[KASHA_VP_VALID] = 1.0f;
      vp[KASHA_VP_DISTANCE] = travelled;
      for (int i = 0; i < KASHA_BINS; ++i) vp[KASHA_VP_D + i] = w[i] * s.rho[i] * k;
#if KASHA_FLUORESCENCE
      for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
        float c = 0.0f;
        for (int i = 0; i < KASHA_BINS; ++i) c += film_row_weight(cmf, r, i) * w[i] * s.ehat[i];
        vp[KASHA_VP_C(KASHA_BINS) + r] = c * k;
      }
      for (int i = 0; i < KASHA_BINS; ++i) vp[KASHA_VP_B(KASHA_BINS, KASHA_FILM_ROWS) + i] = s.a[i];
#endif
      break;
    }
    if (p_gloss <= 0.0f) break;
    float3 mirror = reflect_dir(dir, ns);
    float weight = s.g / p_gloss;
    if (s.mirror) {
      dir = mirror;
    } else {
      float pdf;
      float3 wi = sample_lobe(m, lobes, mirror, rng_next_float(&rng), rng_next_float(&rng), rng_next_float(&rng), &pdf);
      float ci = dot(wi, ns), co = dot(wo, ns);
      if (ci <= 0.0f) break;
      weight *= 2.0f * ci / (ci + co);
      dir = wi;
    }
    for (int i = 0; i < KASHA_BINS; ++i) w[i] *= weight;
    org = x + ns * ray_eps;
  }
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) direct[pixel * KASHA_FILM_ROWS + r] = rows[r];
}
