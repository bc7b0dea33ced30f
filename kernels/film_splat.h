/* Splatting to the film from many work items at once, without float atomics: each film value is
 * a 64-bit fixed-point integer (value × scale) added with atom_add, which is exact and so
 * independent of the order work items run in and of the work-group size. */
#ifndef KASHA_FILM_SPLAT_H
#define KASHA_FILM_SPLAT_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "camera.h"

/* Where a point projects on the pinhole camera's film, and the factor that turns flux leaving
 * it towards the camera into the pixel's average radiance: 1 / (r² cos³θc A_pixel), A_pixel
 * the pixel's area on the image plane at unit distance. Returns the pixel, or -1 off the film. */
inline int camera_pixel(const KCamera* c, float3 x, float* importance) {
  float3 forward = (float3)(c->forward[0], c->forward[1], c->forward[2]);
  float3 right = (float3)(c->right[0], c->right[1], c->right[2]);
  float3 up = (float3)(c->up[0], c->up[1], c->up[2]);
  float3 v = x - camera_position(c);
  float depth = dot(v, forward);
  if (depth <= 0.0f) return -1;
  float3 plane = v / depth - forward;
  float sx = dot(plane, right) / dot(right, right), sy = dot(plane, up) / dot(up, up);
  float px = 0.5f * (sx + 1.0f) * c->width, py = 0.5f * (1.0f - sy) * c->height;
  if (!(px >= 0.0f && px < c->width && py >= 0.0f && py < c->height)) return -1;
  float r2 = dot(v, v), cos_c = depth / sqrt(r2);
  float pixel_area = 4.0f * length(right) * length(up) / (float)(c->width * c->height);
  *importance = 1.0f / (r2 * cos_c * cos_c * cos_c * pixel_area);
  return min((int)py, c->height - 1) * c->width + min((int)px, c->width - 1);
}

/* Adds value × scale, rounded, to a fixed-point film cell; counts values that would overflow. */
inline void splat_fixed(__global long* cell, float value, float scale, int* overflow) {
  float v = value * scale;
  if (!(fabs(v) < 4.0e18f)) {
    *overflow += 1;
    return;
  }
  atom_add(cell, (long)rint(v));
}

#endif
