/* Backward Monte Carlo ray tracing (docs/design.md#backward-transport): camera paths whose colour is a diagonal spectrum
 * or, after a fluorescent bounce, a rank-1 factor (path_weight.h). At each vertex: emission,
 * next-event estimation to an emitting triangle (by solid angle where it subtends enough; MIS with
 * the branch that could have hit it), then one branch — gloss, passive, fluorescent — chosen in
 * proportion to the energy it would bring to the film under equal-energy light, and Russian
 * roulette after the first bounces (roulette.h); a specular dielectric or conductor is one delta
 * bounce (walk_specular). Sample values come from sampler.h.
 * One work item renders one pixel's samples of a launch, so the film needs no atomics; a pass is
 * split into launches of pixel ranges and sample ranges (backward_integrator.cpp). */
#include "shared/launch_records.h"
#include "geometry/camera.h"
#include "transport/camera_walk.h"
#include "film/film_view.h"
#include "sampling/sampler.h"
#include "sampling/sampling.h"
#include "geometry/scene_view.h"

/* One camera path (camera_walk.h) on through every branch; adds its estimate to rows. Returns
 * what the path still carried (relative to its start) if the depth guard cut it, else 0. */
inline float trace_camera_path(const SceneView* s, const FilmView* f, float3 org, float3 dir, Sampler* sampler,
                               float* rows) {
  CameraWalk w;
  walk_start(&w, s, f, org, dir);
  CameraVertex v;
  while (walk_vertex(&w, s, f, sampler, &v, rows)) {
#if KASHA_SCATTERING
    if (v.in_medium) {
      if (!walk_medium_vertex(&w, s, f, &v, rows)) return 0.0f;
      continue;
    }
#endif
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf)) {
      if (!walk_interface(&w, s, f, &v, sampler, rows)) return 0.0f;
      continue;
    }
#endif
    float3 probs = v.probs;
    walk_next_event(&w, s, f, &v, surface_has_lambert(&v.surf), probs, rows);
    float choice = v.u_choice.x;
    if (choice < probs.x) {
      if (!walk_gloss(&w, s, &v, sampler)) return 0.0f;
    } else if (choice < probs.x + probs.y || probs.z <= 0.0f) {
      passive_bounce(&w, &v, probs.y);
#if KASHA_FLUORESCENCE
    } else {
      lambert_bounce(&w, &v, probs.z);
      pw_scatter_fluorescent(&w.p, f, v.surf.ehat, v.surf.a, lambert_weight(&w, &v) / probs.z);
#if KASHA_DISPERSION
      w.bin = -1; /* re-emission spreads the path over the excitation spectrum again */
#endif
#endif
    }
    if (!walk_on(&w, s, f, &v)) return 0.0f;
  }
  return walk_cut(&w, f);
}

__kernel void render_backward(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS,
                              __global float* film,    /* pixels × KASHA_FILM_ROWS, sums over the pass */
                              __global int* rejected,  /* per pixel: samples that were not finite */
                              __global float* cut,     /* per pixel: weight the depth guard cut */
                              KBackwardLaunch launch,
                              KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  const int spp = launch.spp, k_first = launch.k_first, k_last = launch.k_last;
  const uint seed = launch.seed, pass = launch.pass;
  int pixel = launch_pixel(&s.camera, item_first, item_end);
  if (pixel < 0) return;
  int bad = 0;
  float guard = 0.0f;
  Sampler sampler = sampler_start(seed, (uint)pixel, 0, pass, (uint)pixel);
  for (int k = k_first; k < k_last; ++k) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)k);
    float rows[KASHA_FILM_ROWS];
    film_rows_clear(rows);
    float3 o, d = camera_ray(&s.camera, pixel, &sampler, &o);
    guard += trace_camera_path(&s, &f, o, d, &sampler, rows);
    if (film_rows_finite(rows))
      film_add(film, pixel, rows);
    else
      ++bad;
  }
  rejected[pixel] += bad;
  cut[pixel] += guard;
  add_ray_counts(&s, ray_counts);
}
