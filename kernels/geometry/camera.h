/* Primary rays of the pinhole camera (shared_types.h: KCamera). */
#ifndef KASHA_CAMERA_H
#define KASHA_CAMERA_H

#include "shared/shared_types.h"
#include "geometry/pixel_filter.h"

/* Direction through image position (x, y) in pixels, (0, 0) the top-left corner. */
inline float3 camera_direction(const KCamera* c, float x, float y) {
  float sx = 2.0f * x / (float)c->width - 1.0f;
  float sy = 1.0f - 2.0f * y / (float)c->height;
  float3 d = (float3)(c->forward[0], c->forward[1], c->forward[2]) +
             sx * (float3)(c->right[0], c->right[1], c->right[2]) +
             sy * (float3)(c->up[0], c->up[1], c->up[2]);
  return normalize(d);
}

inline float3 camera_position(const KCamera* c) {
  return (float3)(c->position[0], c->position[1], c->position[2]);
}

/* A primary ray direction for pixel `pixel` (row-major) from u ∈ [0,1)²: the point u of the pixel
 * for kasha's unit box, else the pixel's centre plus an offset drawn from the pixel filter. */
inline float3 camera_sample(const KCamera* c, int pixel, float2 u) {
  int px = pixel % c->width, py = pixel / c->width;
  if (c->filter == KASHA_FILTER_PIXEL) return camera_direction(c, px + u.x, py + u.y);
  return camera_direction(c, (float)px + 0.5f + filter_offset(c, 0, u.x), (float)py + 0.5f + filter_offset(c, 1, u.y));
}

/* The pixel a work item renders in a launch of one item per pixel, or -1 for an item past the
 * launch's end (item_end: launches are rounded up to whole work-groups) or past the image. */
inline int launch_pixel(const KCamera* c, int item_end) {
  int pixel = get_global_id(0);
  return pixel < item_end && pixel < c->width * c->height ? pixel : -1;
}

#endif
