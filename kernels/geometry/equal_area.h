/* pbrt-v4's square equal-area octahedral map of the sphere (Clarberg's; util/math.cpp), the
 * spherical camera's default "mapping": equal areas of the unit square are equal solid angles. */
#ifndef KASHA_EQUAL_AREA_H
#define KASHA_EQUAL_AREA_H

#include "sampling/sampling.h"

/* pbrt-v4's WrapEqualAreaSquare: a point a little off the square (a pixel filter's reach) folded
 * back onto the point of the sphere the map continues to. */
inline float2 equal_area_wrap(float2 uv) {
  if (uv.x < 0.0f) {
    uv.x = -uv.x;
    uv.y = 1.0f - uv.y;
  } else if (uv.x > 1.0f) {
    uv.x = 2.0f - uv.x;
    uv.y = 1.0f - uv.y;
  }
  if (uv.y < 0.0f) {
    uv.x = 1.0f - uv.x;
    uv.y = -uv.y;
  } else if (uv.y > 1.0f) {
    uv.x = 1.0f - uv.x;
    uv.y = 2.0f - uv.y;
  }
  return uv;
}

/* EqualAreaSquareToSphere: the direction of square point p in [0, 1]². */
inline float3 equal_area_to_sphere(float2 p) {
  float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
  float up = fabs(u), vp = fabs(v);
  float signed_distance = 1.0f - (up + vp);
  float r = 1.0f - fabs(signed_distance);
  float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * KASHA_PI / 4.0f;
  float z = copysign(1.0f - r * r, signed_distance);
  float s = r * sqrt(fmax(2.0f - r * r, 0.0f));
  return (float3)(copysign(cos(phi), u) * s, copysign(sin(phi), v) * s, z);
}

/* EqualAreaSphereToSquare, its inverse for a unit direction (atan exact where pbrt-v4 fits a
 * polynomial). */
inline float2 equal_area_to_square(float3 d) {
  float x = fabs(d.x), y = fabs(d.y);
  float r = sqrt(fmax(1.0f - fabs(d.z), 0.0f));
  float a = fmax(x, y), b = fmin(x, y);
  float phi = a == 0.0f ? 0.0f : atan(b / a) * 2.0f / KASHA_PI;
  if (x < y) phi = 1.0f - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.0f) {
    float t = u;
    u = 1.0f - v;
    v = 1.0f - t;
  }
  return (float2)(0.5f * (copysign(u, d.x) + 1.0f), 0.5f * (copysign(v, d.y) + 1.0f));
}

#endif
