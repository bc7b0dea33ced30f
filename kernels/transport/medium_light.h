/* Light paths that start inside an emitting medium (docs/media.md#emitting-media), for the
 * integrators whose light paths must carry all of the scene's light (forward, photon, ppm): a
 * medium is picked with its share of the emitted power (KMedium::light_pick, set by the host;
 * their sum is the share of light paths that start in media), a point uniform in the box that
 * holds its region, and the point kept where it is in that medium — which medium a point is in is
 * found as a ray finds it, from the first medium boundary along a ray from it. The point's weight
 * is what the medium emits there over the uniform density, so the estimate is unbiased wherever
 * the box holds the region. */
#ifndef KASHA_MEDIUM_LIGHT_H
#define KASHA_MEDIUM_LIGHT_H

#include "geometry/scene_view.h"
#include "media/medium.h"
#include "media/medium_emission.h"

#if KASHA_MEDIA && KASHA_MEDIUM_EMISSION
#define KASHA_MEDIUM_LIGHTS 1
#else
#define KASHA_MEDIUM_LIGHTS 0
#endif

#if KASHA_MEDIUM_LIGHTS
/* The share of light paths that start in a medium: the media's picks summed. */
inline float medium_light_share(const SceneView* s) {
  float share = 0.0f;
  for (int m = 0; m < KASHA_MEDIA_COUNT; ++m) share += s->media[m].light_pick;
  return share;
}

/* The medium u (below medium_light_share) picks; *rest: u's place within its pick, in [0, 1). */
inline int medium_light_pick(const SceneView* s, float u, float* rest) {
  int chosen = 0;
  float below = 0.0f, at = 0.0f;
  for (int m = 0; m < KASHA_MEDIA_COUNT; ++m) {
    float pick = s->media[m].light_pick;
    if (!(pick > 0.0f)) continue;
    chosen = m, at = below; /* rounding past the last pick keeps the last that has one */
    if (u < below + pick) break;
    below += pick;
  }
  *rest = fmin(fmax((u - at) / s->media[chosen].light_pick, 0.0f), 0x1.fffffep-1f);
  return chosen;
}

/* The point of m's box at u in the unit cube (KMedium::light_box, row-major 3 × 4). */
inline float3 medium_light_point(const __global KMedium* m, float3 u) {
  const __global float* a = m->light_box;
  return (float3)(a[0] * u.x + a[1] * u.y + a[2] * u.z + a[3], a[4] * u.x + a[5] * u.y + a[6] * u.z + a[7],
                  a[8] * u.x + a[9] * u.y + a[10] * u.z + a[11]);
}

/* Whether x is in medium m, looking along dir: the side of the first medium boundary the ray
 * meets that faces x (other surfaces and interfaces between equal media are passed, as rays keep
 * their medium there); past every boundary, in m if m is the one outside them all. Without
 * boundaries every point is in the camera's medium. */
inline bool medium_holds(const SceneView* s, int m, float3 x, float3 dir) {
#if KASHA_MEDIUM_BOUNDARIES
  /* Surfaces inside a medium (not its boundaries) are passed: a generous guard, for dense ones. */
  for (int k = 0; k < 16 * KASHA_MAX_INTERFACES; ++k) {
    HitPoint h;
    if (!intersect_surface(s, x, dir, &h)) return s->media[m].light_outer != 0;
    KTriMedia tm = s->tri_media[h.tri];
    if (tm.inside != tm.outside) return (dot(dir, h.n) > 0.0f ? tm.inside : tm.outside) == m;
    x = h.x + (dot(dir, h.n) > 0.0f ? h.n : -h.n) * h.eps;
  }
  return false;
#else
  return m == s->camera_medium;
#endif
}
#endif

#endif
