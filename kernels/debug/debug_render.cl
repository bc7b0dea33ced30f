/* First-hit views: emitted radiance (the directly visible emission term, jittered over each pixel),
 * geometric normals and material albedo. Each work item owns one pixel, so no atomics are needed.
 * Defines: KASHA_BINS (N), KASHA_SPECTRAL_FILM (0: rows are X,Y,Z; 1: rows are the N bins),
 * KASHA_FILM_ROWS (3 or N). */
#include "geometry/camera.h"
#include "shared/color_constants.h"
#include "film/film_view.h"
#include "geometry/hit_point.h"
#include "materials/hit_material.h"
#include "media/medium.h"
#include "sampling/sampler.h"
#include "geometry/scene_view.h"

#define VIEW_EMISSION 0
#define VIEW_NORMALS 1
#define VIEW_ALBEDO 2

__constant float kSrgbToXyz[3][3] = KASHA_SRGB_TO_XYZ;

inline void add_rgb_as_xyz(float* rows, float3 rgb) {
  for (int k = 0; k < 3; ++k)
    rows[k] += kSrgbToXyz[k][0] * rgb.x + kSrgbToXyz[k][1] * rgb.y + kSrgbToXyz[k][2] * rgb.z;
}

__kernel void render_debug(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS,
                           __global float* film, /* pixels × KASHA_FILM_ROWS, sums over the pass */
                           int view, int spp, uint seed, uint pass,
                  KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int pixel = launch_pixel(&s.camera, item_first, item_end);
  if (pixel < 0) return;
  Sampler sampler = sampler_start(seed, (uint)pixel, 0, pass, (uint)pixel);
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  for (int k = 0; k < spp; ++k) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)k);
    HitPoint h;
    float3 o, d = camera_ray(&s.camera, pixel, &sampler, &o);
#if KASHA_MEDIA
    /* The first surface: interface shapes (media's boundaries) are not surfaces; the media are
     * not shown (a first-hit view). */
    int medium = s.camera_medium;
    MediaTrail trail;
    trail_clear(&trail);
    if (!intersect_through(&s, o, d, &medium, &trail, &h)) continue;
#else
    if (!intersect_surface(&s, o, d, &h))
      continue;
#endif
    if (view == VIEW_EMISSION) {
      /* Emitters radiate from their front side only. */
      if (h.emitter >= 0 && h.front) film_rows(&f, 0, emitter_spectrum(&s, h.emitter), 0, 1.0f, rows);
    } else if (view == VIEW_NORMALS) {
      add_rgb_as_xyz(rows, 0.5f * hit_front(&h) + 0.5f);
    } else {
      const __global KMaterial* m = &s.materials[h.material];
      for (int c = 0; c < 3; ++c) rows[c] += m->albedo_xyz[c];
    }
  }
  film_add(film, pixel, rows);
  add_ray_counts(&s, ray_counts);
}
