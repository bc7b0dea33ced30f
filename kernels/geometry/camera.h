/* Primary rays of the camera (shared_types.h: KCamera), as pbrt-v4's cameras.cpp generates them,
 * and where a light path connected to the camera meets it. */
#ifndef KASHA_CAMERA_H
#define KASHA_CAMERA_H

#include "shared/launch_range.h"
#include "shared/shared_types.h"
#include "geometry/equal_area.h"
#include "geometry/pixel_filter.h"
#include "sampling/sampling.h"

inline float3 camera_vec(const float* a) { return (float3)(a[0], a[1], a[2]); }

inline float3 camera_position(const KCamera* c) { return camera_vec(c->position); }

/* The screen point of image position (x, y) in pixels, (0, 0) the top-left corner. */
inline float2 camera_screen(const KCamera* c, float x, float y) {
  return (float2)(2.0f * x / (float)c->width - 1.0f + c->center[0], 1.0f - 2.0f * y / (float)c->height + c->center[1]);
}

/* The perspective camera's pinhole direction through image position (x, y). */
inline float3 camera_direction(const KCamera* c, float x, float y) {
  float2 s = camera_screen(c, x, y);
  float3 d = camera_vec(c->forward) + s.x * camera_vec(c->right) + s.y * camera_vec(c->up);
  return normalize(d);
}

/* A pixel's area: on the image plane at unit distance (perspective), in the world (orthographic). */
inline float camera_pixel_area(const KCamera* c) {
  return 4.0f * length(camera_vec(c->right)) * length(camera_vec(c->up)) / (float)(c->width * c->height);
}

/* The spherical camera's direction through image position (x, y): pbrt-v4's map of the square
 * (u, v) = (x / width, y / height), its y and z swapped (the map's pole is the camera's up). */
inline float3 camera_sphere_direction(const KCamera* c, float x, float y) {
  float2 uv = (float2)(x / (float)c->width, y / (float)c->height);
  float3 d;
  if (c->type == KASHA_CAMERA_EQUIRECTANGULAR) {
    float theta = KASHA_PI * uv.y, phi = 2.0f * KASHA_PI * uv.x;
    d = (float3)(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
  } else {
    d = equal_area_to_sphere(equal_area_wrap(uv));
  }
  return d.x * camera_vec(c->right) + d.z * camera_vec(c->up) + d.y * camera_vec(c->forward);
}

/* The inverse: the image position of unit direction w, and in *solid the solid angle per unit
 * of image area (pixels²) there. */
inline float2 camera_sphere_film(const KCamera* c, float3 w, float* solid) {
  float lx = dot(w, camera_vec(c->right)), ly = dot(w, camera_vec(c->up)), lz = dot(w, camera_vec(c->forward));
  float pixels = (float)(c->width * c->height);
  float2 uv;
  if (c->type == KASHA_CAMERA_EQUIRECTANGULAR) {
    float theta = acos(clamp(ly, -1.0f, 1.0f)), phi = atan2(lz, lx);
    if (phi < 0.0f) phi += 2.0f * KASHA_PI;
    uv = (float2)(phi / (2.0f * KASHA_PI), theta / KASHA_PI);
    *solid = 2.0f * KASHA_PI * KASHA_PI * sin(theta) / pixels;
  } else {
    uv = equal_area_to_square((float3)(lx, lz, ly));
    *solid = 4.0f * KASHA_PI / pixels;
  }
  return (float2)(uv.x * (float)c->width, uv.y * (float)c->height);
}

/* The solid angle a pixel's film area spreads over around a camera ray's direction dir (from its
 * origin): the camera's inverse density of dir per solid angle, one sample a pixel. Orthographic
 * (a delta in direction): the pixel's world area, the inverse density per area once divided by
 * the squared distance to the first vertex (vcm_camera_path.h). */
inline float camera_pixel_solid_angle(const KCamera* c, float3 dir) {
  if (c->type == KASHA_CAMERA_ORTHOGRAPHIC) return camera_pixel_area(c);
  if (c->type != KASHA_CAMERA_PERSPECTIVE) {
    float solid;
    camera_sphere_film(c, dir, &solid);
    return solid;
  }
  float cos_c = dot(dir, normalize(camera_vec(c->forward)));
  return camera_pixel_area(c) * cos_c * cos_c * cos_c;
}

/* The thin lens's dimension pair under Sobol numbers: past every path vertex's, so drawing it
 * (only with a lens) moves no other dimension. */
#define KASHA_LENS_PAIR 0x10000u

inline float2 camera_lens_sample(Sampler* s) {
#if KASHA_SOBOL
  uint pair = s->pair;
  sampler_at(s, KASHA_LENS_PAIR);
  float2 u = sample_2d(s);
  sampler_at(s, pair);
  return u;
#else
  return sample_2d(s);
#endif
}

/* A point of the thin lens from u ∈ [0,1)² (pbrt-v4's concentric disk). */
inline float3 camera_lens_point(const KCamera* c, float2 u) {
  float2 l = c->lens_radius * sample_disk_concentric(u);
  return camera_position(c) + l.x * normalize(camera_vec(c->right)) + l.y * normalize(camera_vec(c->up));
}

/* A primary ray for pixel `pixel` (row-major): its origin in *o, its direction returned. The
 * film point is the point u of the pixel for kasha's unit box, else the pixel's centre plus an
 * offset drawn from the pixel filter; a thin lens draws a second pair (camera_lens_sample). */
inline float3 camera_ray(const KCamera* c, int pixel, Sampler* sampler, float3* o) {
  float2 u = sample_2d(sampler);
  int px = pixel % c->width, py = pixel / c->width;
  float x = (float)px + u.x, y = (float)py + u.y;
  if (c->filter != KASHA_FILTER_PIXEL) {
    x = (float)px + 0.5f + filter_offset(c, 0, u.x);
    y = (float)py + 0.5f + filter_offset(c, 1, u.y);
  }
  *o = camera_position(c);
  if (c->type >= KASHA_CAMERA_EQUAL_AREA) return camera_sphere_direction(c, x, y);
  if (c->type == KASHA_CAMERA_ORTHOGRAPHIC) {
    float2 s = camera_screen(c, x, y);
    *o += s.x * camera_vec(c->right) + s.y * camera_vec(c->up);
    return normalize(camera_vec(c->forward));
  }
  float3 d = camera_direction(c, x, y);
  if (c->lens_radius > 0.0f) {
    /* pbrt-v4's thin lens: the pinhole ray's point at the focal distance, seen from the lens. */
    float3 focus = *o + d * (c->focal_distance / dot(d, camera_vec(c->forward)));
    *o = camera_lens_point(c, camera_lens_sample(sampler));
    d = normalize(focus - *o);
  }
  return d;
}

/* Where a light path's vertex x connects to the camera: the pinhole, the orthographic film point
 * in front of which x lies, or a point of the thin lens (pbrt-v4's PerspectiveCamera::SampleWi)
 * drawn from a hash of x — x is a continuous random variable, so its bits serve as a fresh
 * number and the same x always meets the same lens point. */
inline float3 camera_point(const KCamera* c, float3 x) {
  float3 p = camera_position(c);
  if (c->type == KASHA_CAMERA_ORTHOGRAPHIC) {
    float3 f = normalize(camera_vec(c->forward));
    return x - dot(x - p, f) * f;
  }
  if (c->type != KASHA_CAMERA_PERSPECTIVE || !(c->lens_radius > 0.0f)) return p;
  uint h = hash_combine(hash_combine(hash_u32(as_uint(x.x)), as_uint(x.y)), as_uint(x.z));
  float2 u = (float2)((float)(h >> 8) * 0x1p-24f, (float)(hash_u32(h) >> 8) * 0x1p-24f);
  return camera_lens_point(c, u);
}

/* The pixel a work item renders in a launch of one item per pixel, or -1 for an item past the
 * launch's end (shared/launch_range.h) or past the image. */
inline int launch_pixel(const KCamera* c, int item_first, int item_end) {
  int pixel = launch_item(item_first);
  return pixel < item_end && pixel < c->width * c->height ? pixel : -1;
}

#endif
