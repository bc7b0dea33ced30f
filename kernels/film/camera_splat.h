/* Light paths connected to the camera and splatted to the film (film_splat.h): light
 * tracing (forward.cl) and vertex connection and merging's light subpaths (vcm.cl). */
#ifndef KASHA_CAMERA_SPLAT_H
#define KASHA_CAMERA_SPLAT_H

#include "film/film_splat.h"
#include "film/film_view.h"
#include "geometry/hit_point.h"
#include "geometry/scene_view.h"
#include "media/medium.h"

typedef struct {
  __global ulong* film; /* 2 words (lo, hi) per pixel and row, film_splat.h */
  int film_shift;       /* a splat of value v adds v · 2^film_shift units */
  int overflow;
} SplatTarget;

/* Whether x (normal ns on the lit side) sees the camera: its pixel, and the factor cos·importance
 * that turns radiance leaving x (per nm, before that factor) into the pixel's average. In a scene
 * with media the connection leaves x in `medium` and passes interfaces, *tr its transmittance per
 * bin (media/medium.h's segment_clear); *tr is null where no medium attenuates it. */
inline bool camera_connection(const SceneView* s, float3 x, float3 ns, float eps, int medium, int* pixel, float* k,
                              const __global float** tr) {
  *tr = 0;
  float importance;
  float3 at = camera_point(&s->camera, x);
  *pixel = camera_pixel(&s->camera, x, at, &importance);
  if (*pixel < 0) return false;
  float3 to_camera = at - x;
  float dist = length(to_camera);
  float3 dir = to_camera / dist;
  float cos_x = dot(ns, dir);
  if (cos_x <= 0.0f) return false;
  if (dist - eps <= 0.0f) return false;
#if KASHA_MEDIA
  if (!segment_clear(s, x, ns, eps, dir, dist, 0.0f, medium, tr)) return false;
#else
  ++s->rays->shadow;
  AlphaTables alpha = scene_alpha(s);
  BvhTables bvh = scene_bvh(s);
  if (bvh_occluded(&bvh, &alpha, x + ns * eps, dir, 0.0f, dist - eps)) return false;
#endif
  *k = cos_x * importance;
  return true;
}

#if KASHA_SCATTERING
/* Whether a point x inside a medium (no surface, so no cosine and no offset) sees the camera: its
 * pixel, the factor `importance` alone in *k, and the connection's transmittance *tr as above. */
inline bool camera_connection_from_medium(const SceneView* s, float3 x, int medium, int* pixel, float* k,
                                          const __global float** tr) {
  *tr = 0;
  float importance;
  float3 at = camera_point(&s->camera, x);
  *pixel = camera_pixel(&s->camera, x, at, &importance);
  if (*pixel < 0) return false;
  float dist = length(at - x);
  if (!(dist > 0.0f)) return false;
  if (!segment_clear(s, x, (float3)(0.0f, 0.0f, 0.0f), 0.0f, (at - x) / dist, dist, 0.0f, medium, tr)) return false;
  *k = importance;
  return true;
}
#endif

inline void splat_rows(SplatTarget* t, int pixel, const float* rows) {
  __global ulong* cell = t->film + 2 * (long)pixel * KASHA_FILM_ROWS;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r)
    if (rows[r] != 0.0f) splat_fixed(cell + 2 * r, rows[r], t->film_shift, &t->overflow);
}

#endif
