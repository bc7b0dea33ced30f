/* Splatting to the film from many work items at once, without float atomics: each film value is
 * a 128-bit unsigned fixed-point integer (value · 2^shift) held as two 64-bit words (lo, hi) and
 * added with atom_add and an explicit carry. Integer sums are exact, so the film does not depend
 * on the order work items run in nor on the work-group size. */
#ifndef KASHA_FILM_SPLAT_H
#define KASHA_FILM_SPLAT_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "geometry/camera.h"

/* Where the connection from camera point `at` (camera_point) to x lands on the film, and the
 * factor that turns flux leaving x towards the camera into the pixel's average radiance: the
 * image area per area of x, for a perspective camera 1 / (r² cos³θc A_pixel), A_pixel the
 * pixel's area on the image plane at unit distance (a thin lens: r and θc from the lens point,
 * the film point where the pinhole sees the ray's point at the focal distance; the lens area
 * cancels between pbrt-v4's We and its lens density), for an orthographic one 1 / A_pixel in the
 * world, for a spherical one 1 / (r² dω/dA_image). Times the pixel filter's splat factor
 * (geometry/pixel_filter.h). Returns the pixel, or -1 off the film. */
inline int camera_pixel(const KCamera* c, float3 x, float3 at, float* importance) {
  float3 forward = (float3)(c->forward[0], c->forward[1], c->forward[2]);
  float3 right = (float3)(c->right[0], c->right[1], c->right[2]);
  float3 up = (float3)(c->up[0], c->up[1], c->up[2]);
  float3 v = x - at;
  float px, py;
  if (c->type >= KASHA_CAMERA_EQUAL_AREA) {
    float r2 = dot(v, v), solid;
    float2 film = camera_sphere_film(c, v / sqrt(r2), &solid);
    if (!(solid > 0.0f)) return -1;
    px = film.x;
    py = film.y;
    *importance = 1.0f / (r2 * solid);
  } else {
    float depth = dot(v, forward);
    if (depth <= 0.0f) return -1;
    float3 plane;
    if (c->type == KASHA_CAMERA_ORTHOGRAPHIC) {
      plane = x - camera_position(c);
      *importance = 1.0f / camera_pixel_area(c);
    } else {
      float r2 = dot(v, v), cos_c = depth / sqrt(r2);
      *importance = 1.0f / (r2 * cos_c * cos_c * cos_c * camera_pixel_area(c));
      plane = v / depth - forward;
      if (c->lens_radius > 0.0f) {
        float3 q = at + v * (c->focal_distance / depth) - camera_position(c);
        plane = q / dot(q, forward) - forward;
      }
    }
    float sx = dot(plane, right) / dot(right, right) - c->center[0], sy = dot(plane, up) / dot(up, up) - c->center[1];
    px = 0.5f * (sx + 1.0f) * c->width;
    py = 0.5f * (1.0f - sy) * c->height;
  }
  if (!filter_reaches(c, px, py)) return -1;
  return filter_splat_pixel(c, px, py, importance);
}

/* Adds value · 2^shift, rounded to an integer, to the 128-bit cell (cell[0] = lo, cell[1] = hi);
 * negative, non-finite or too large values (≥ 2^127 units, the headroom the host's shift leaves
 * for the cell's sum) are counted as rejected instead. */
inline void splat_fixed(__global ulong* cell, float value, int shift, int* rejected) {
  float f = rint(ldexp(value, shift));
  if (!(f >= 0.0f && f < 0x1p127f)) {
    *rejected += 1;
    return;
  }
  /* Exact in float: f < 2^127 is an integer of 24 significant bits, so f·2^-64 and its floor are
   * exact and hi·2^64 is f itself or a multiple of f's ulp; lo = f − hi·2^64 < 2^64 is then a
   * multiple of that ulp with fewer than 24 significant bits: the subtraction is exact. */
  float hi_f = floor(f * 0x1p-64f);
  ulong hi = (ulong)hi_f, lo = (ulong)(f - hi_f * 0x1p64f);
  if (lo != 0 && atom_add(cell, lo) + lo < lo) hi += 1; /* the low word wrapped: carry */
  if (hi != 0) atom_add(cell + 1, hi);
}

#endif
