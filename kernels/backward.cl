/* Backward Monte Carlo ray tracing (docs/design.md#backward-transport): camera paths whose colour is a diagonal spectrum
 * or, after a fluorescent bounce, a rank-1 factor (path_weight.h). At each vertex: emission,
 * next-event estimation to an emitting triangle (by solid angle where it subtends enough; MIS with
 * the branch that could have hit it), then one branch — gloss, passive, fluorescent — chosen in
 * proportion to the energy it would bring to the film under equal-energy light, and Russian
 * roulette after the first bounces (roulette.h). Sample values come from sampler.h.
 * One work item renders one pixel's samples of a launch, so the film needs no atomics; a pass is
 * split into launches of pixel ranges and sample ranges (backward_integrator.cpp). */
#include "camera.h"
#include "film_view.h"
#include "gloss_lobe.h"
#include "hit_point.h"
#include "lights.h"
#include "next_event.h"
#include "branch_choice.h"
#include "path_weight.h"
#include "roulette.h"
#include "sampler.h"
#include "sampling.h"
#include "scene_view.h"
#include "surface.h"

/* Dimension pairs of the sampler per path vertex: (branch choice, roulette), the light (triangle
 * and point), the direction, and (the lobe's azimuth, —) drawn only for a lobe; pair 0 is the
 * pixel position. */
#define PAIRS_PER_VERTEX 4

/* One camera path; adds its estimate to rows. Returns what the path still carried (relative to
 * its start) if the depth guard cut it, else 0. */
inline float trace_camera_path(const SceneView* s, const FilmView* f, float3 org, float3 dir, Sampler* sampler,
                               float* rows) {
  PathWeight p;
  pw_init(&p, f);
  const float start = pw_magnitude(&p, f);
  bool specular = true; /* the camera ray, or a mirror bounce: emission is not also sampled by NEE */
  float prev_pdf = 0.0f;
  float3 prev_x = org; /* the previous vertex itself (org is offset off its surface) */
  for (int depth = 0; depth < KASHA_MAX_PATH_DEPTH; ++depth) {
    HitPoint h;
    if (!intersect_scene(s, org, dir, &h)) return 0.0f;
    float3 wo = -dir, ns = h.ns, x = h.x;

    if (h.emitter >= 0 && h.front) {
      float weight = 1.0f;
      if (!specular) weight = mis_weight(prev_pdf, light_pdf_from(s, h.tri, prev_x, x, dot(h.n, wo)));
      pw_add(&p, f, emitter_spectrum(s, h.emitter), 0, weight, rows);
    }

    Surface surf;
    load_surface(s, h.material, &surf);
    float3 probs = branch_probabilities(&p, f, &surf);
    if (probs.x + probs.y + probs.z <= 0.0f) return 0.0f;
    sampler_at(sampler, 1 + depth * PAIRS_PER_VERTEX);
    float2 u_choice = sample_2d(sampler), u_light = sample_2d(sampler), u_dir = sample_2d(sampler);
    if (s->light_count > 0 && (surface_has_lambert(&surf) || (surf.g > 0.0f && !surf.mirror)))
      next_event(&p, s, f, &surf, x, ns, h.eps, wo, probs, u_light, rows);

    float choice = u_choice.x;
    if (choice < probs.x) {
      /* Gloss: white, weight g (times the lobe's cosine ratio), below the horizon absorbed. */
      float3 mirror = reflect_dir(dir, ns);
      if (surf.mirror) {
        dir = mirror;
        specular = true;
        pw_scatter_diagonal(&p, 0, surf.g / probs.x);
      } else {
        float pdf;
        float3 wi = sample_lobe(surf.m, s->lobes, mirror, u_dir.x, u_dir.y, sample_2d(sampler).x, &pdf);
        float ci = dot(wi, ns), co = dot(wo, ns);
        if (ci <= 0.0f) return 0.0f;
        dir = wi;
        specular = false;
        prev_pdf = probs.x * pdf;
        pw_scatter_diagonal(&p, 0, surf.g * 2.0f * ci / (ci + co) / probs.x);
      }
    } else if (choice < probs.x + probs.y || probs.z <= 0.0f) {
      dir = sample_cosine_hemisphere(ns, u_dir.x, u_dir.y);
      specular = false;
      prev_pdf = probs.y * cosine_hemisphere_pdf(dot(dir, ns));
      pw_scatter_diagonal(&p, surf.rho, 1.0f / probs.y);
#if KASHA_FLUORESCENCE
    } else {
      dir = sample_cosine_hemisphere(ns, u_dir.x, u_dir.y);
      specular = false;
      prev_pdf = probs.z * cosine_hemisphere_pdf(dot(dir, ns));
      pw_scatter_fluorescent(&p, f, surf.ehat, surf.a, 1.0f / probs.z);
#endif
    }
    if (depth >= KASHA_CAMERA_ROULETTE_FROM) {
      float keep = roulette(pw_magnitude(&p, f) / start, u_choice.y);
      if (keep == 0.0f) return 0.0f;
      if (keep != 1.0f) pw_scatter_diagonal(&p, 0, keep);
    }
    prev_x = x;
    org = x + ns * h.eps;
  }
  return pw_magnitude(&p, f) / start;
}

__kernel void render_backward(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS,
                              __global float* film,    /* pixels × KASHA_FILM_ROWS, sums over the pass */
                              __global int* rejected,  /* per pixel: samples that were not finite */
                              __global float* cut,     /* per pixel: weight the depth guard cut */
                              int spp, int k_first, int k_last, /* this launch: samples [k_first, k_last) */
                              uint seed, uint pass,
                  int item_end /* launches are rounded up to whole work-groups */) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int pixel = get_global_id(0);
  if (pixel >= item_end) return;
  if (pixel >= camera.width * camera.height) return;
  int bad = 0;
  float guard = 0.0f;
  Sampler sampler = sampler_start(seed, (uint)pixel, 0, pass, (uint)pixel);
  for (int k = k_first; k < k_last; ++k) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)k);
    float rows[KASHA_FILM_ROWS];
    film_rows_clear(rows);
    guard += trace_camera_path(&s, &f, camera_position(&camera), camera_sample(&camera, pixel, sample_2d(&sampler)),
                               &sampler, rows);
    if (film_rows_finite(rows))
      film_add(film, pixel, rows);
    else
      ++bad;
  }
  rejected[pixel] += bad;
  cut[pixel] += guard;
  add_ray_counts(&s, ray_counts);
}
