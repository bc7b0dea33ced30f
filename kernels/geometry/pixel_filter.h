/* The pixel filter, as pbrt-v4 applies it (docs/formats.md#camera). A pixel's value is the
 * average of the radiance arriving at film points x weighted by the filter's density
 * p(x − centre), the filter normalized to integrate to 1 and separable, p = px(x) py(y).
 * - Camera paths sample the offset from the pixel's centre with the density itself (pbrt-v4's
 *   filter importance sampling: every sample weighs the same).
 * - Light splats (light tracing's t = 1) reach the pixels whose centres lie within the radius:
 *   one of them is chosen with probability p(x − c) / S per axis and the splat scaled by S, so
 *   each pixel gets p(x − c) on average with one atomic add. The choice hashes the film point
 *   (a continuous random variable: its bits are as good as a fresh random number) so no
 *   integrator's random-number stream changes.
 * KASHA_FILTER_PIXEL is kasha's own unit box: the sample's position in the pixel, as before. */
#ifndef KASHA_PIXEL_FILTER_H
#define KASHA_PIXEL_FILTER_H

#include "shared/shared_types.h"
#include "sampling/sampler.h"

/* The offset along one axis (pixels) for u in [0, 1). */
inline float filter_offset(const KCamera* c, int axis, float u) {
  float r = c->filter_radius[axis];
  if (c->filter == KASHA_FILTER_BOX) return (2.0f * u - 1.0f) * r;
  if (c->filter == KASHA_FILTER_TRIANGLE)
    return u < 0.5f ? r * (sqrt(2.0f * u) - 1.0f) : r * (1.0f - sqrt(2.0f - 2.0f * u));
  /* The table: the side from u's half, the bin from the half axis's cumulative mass, then
   * uniform inside the bin. */
  float v = u < 0.5f ? 1.0f - 2.0f * u : 2.0f * u - 1.0f;
  int b = 0;
  while (b < KASHA_FILTER_BINS - 1 && c->filter_cdf[axis][b] <= v) ++b;
  float lo = b > 0 ? c->filter_cdf[axis][b - 1] : 0.0f, hi = c->filter_cdf[axis][b];
  float t = hi > lo ? clamp((v - lo) / (hi - lo), 0.0f, 1.0f) : 0.5f;
  float x = r * ((float)b + t) / (float)KASHA_FILTER_BINS;
  return u < 0.5f ? -x : x;
}

/* The filter's density along one axis at offset x (pixels). */
inline float filter_density(const KCamera* c, int axis, float x) {
  float r = c->filter_radius[axis], ax = fabs(x);
  if (!(ax < r)) return 0.0f;
  if (c->filter == KASHA_FILTER_BOX) return 0.5f / r;
  if (c->filter == KASHA_FILTER_TRIANGLE) return (r - ax) / (r * r);
  int b = min((int)(ax / r * (float)KASHA_FILTER_BINS), KASHA_FILTER_BINS - 1);
  float mass = c->filter_cdf[axis][b] - (b > 0 ? c->filter_cdf[axis][b - 1] : 0.0f);
  return 0.5f * mass * (float)KASHA_FILTER_BINS / r;
}

/* A film position inside the image's bounds widened by the filter's radius. */
inline bool filter_reaches(const KCamera* c, float px, float py) {
  float rx = c->filter == KASHA_FILTER_PIXEL ? 0.0f : c->filter_radius[0];
  float ry = c->filter == KASHA_FILTER_PIXEL ? 0.0f : c->filter_radius[1];
  return px >= -rx && px < c->width + rx && py >= -ry && py < c->height + ry;
}

/* One axis of a splat at film coordinate p: the pixel chosen among those whose centre lies within
 * the radius, with probability density(p − centre) / S; returns it (possibly off the image) and
 * multiplies *scale by S. */
inline int filter_splat_axis(const KCamera* c, int axis, float p, float u, float* scale) {
  float r = c->filter_radius[axis];
  int first = (int)ceil(p - r - 0.5f), last = (int)floor(p + r - 0.5f);
  float sum = 0.0f;
  for (int i = first; i <= last; ++i) sum += filter_density(c, axis, p - ((float)i + 0.5f));
  float target = u * sum, run = 0.0f;
  int chosen = last;
  for (int i = first; i <= last; ++i) {
    run += filter_density(c, axis, p - ((float)i + 0.5f));
    if (target < run) {
      chosen = i;
      break;
    }
  }
  *scale *= sum;
  return chosen;
}

/* The pixel a splat at film position (px, py) goes to, or -1; *scale gets the splat's factor. */
inline int filter_splat_pixel(const KCamera* c, float px, float py, float* scale) {
  if (c->filter == KASHA_FILTER_PIXEL)
    return min((int)py, c->height - 1) * c->width + min((int)px, c->width - 1);
  uint h = hash_combine(hash_u32(as_uint(px)), as_uint(py));
  float ux = (float)(h >> 8) * 0x1p-24f, uy = (float)(hash_u32(h) >> 8) * 0x1p-24f;
  int ix = filter_splat_axis(c, 0, px, ux, scale), iy = filter_splat_axis(c, 1, py, uy, scale);
  if (ix < 0 || ix >= c->width || iy < 0 || iy >= c->height) return -1;
  return iy * c->width + ix;
}

#endif
