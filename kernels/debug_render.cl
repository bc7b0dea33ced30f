/* First-hit views: emitted radiance (the directly visible emission term, jittered over each pixel),
 * geometric normals and material albedo. Each work item owns one pixel, so no atomics are needed.
 * Defines: KASHA_BINS (N), KASHA_SPECTRAL_FILM (0: rows are X,Y,Z; 1: rows are the N bins),
 * KASHA_FILM_ROWS (3 or N). */
#include "hit_point.h"
#include "camera.h"
#include "color_constants.h"
#include "rng.h"
#include "scene_params.h"

#define VIEW_EMISSION 0
#define VIEW_NORMALS 1
#define VIEW_ALBEDO 2

__constant float kSrgbToXyz[3][3] = KASHA_SRGB_TO_XYZ;

inline void add_rgb_as_xyz(float* rows, float3 rgb) {
  for (int k = 0; k < 3; ++k)
    rows[k] += kSrgbToXyz[k][0] * rgb.x + kSrgbToXyz[k][1] * rgb.y + kSrgbToXyz[k][2] * rgb.z;
}

__kernel void render_debug(KCamera camera, KASHA_SCENE_PARAMS,
                           __global const float* cmf,              /* 3 x N: x̄ȳz̄ of each bin times its width */
                           __global float* film,                   /* pixels x KASHA_FILM_ROWS, sums */
                           int view, int spp, uint seed, uint pass) {
  int pixel = get_global_id(0);
  if (pixel >= camera.width * camera.height) return;
  int px = pixel % camera.width, py = pixel / camera.width;
  Rng rng = rng_seed(seed, pass, (uint)pixel);
  float rows[KASHA_FILM_ROWS];
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] = 0.0f;
  float3 org = camera_position(&camera);

  for (int s = 0; s < spp; ++s) {
    float3 dir = camera_direction(&camera, px + rng_next_float(&rng), py + rng_next_float(&rng));
    HitPoint h;
    if (!intersect_scene(nodes, tris, org, dir, &h)) continue;
    float3 n = h.n;
    if (view == VIEW_EMISSION) {
      /* Emitters radiate from their front side only. */
      if (h.emitter < 0 || !h.front) continue;
      const __global float* le = emitter_radiance + h.emitter * KASHA_BINS;
#if KASHA_SPECTRAL_FILM
      for (int i = 0; i < KASHA_BINS; ++i) rows[i] += le[i];
#else
      for (int i = 0; i < KASHA_BINS; ++i) {
        rows[0] += cmf[i] * le[i];
        rows[1] += cmf[KASHA_BINS + i] * le[i];
        rows[2] += cmf[2 * KASHA_BINS + i] * le[i];
      }
#endif
    } else if (view == VIEW_NORMALS) {
      add_rgb_as_xyz(rows, 0.5f * n + 0.5f);
    } else {
      const __global KMaterial* m = &materials[h.material];
      for (int k = 0; k < 3; ++k) rows[k] += m->albedo_xyz[k];
    }
  }
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) film[pixel * KASHA_FILM_ROWS + r] = rows[r];
}
