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

/* EqualAreaSquareToSphere: the direction of square point p in [0, 1]²; and its inverse,
 * EqualAreaSphereToSquare, for a unit direction (atan exact where pbrt-v4 fits a polynomial).
 * Environment images and the spherical camera share them. */
inline float3 equal_area_to_sphere(float2 p) {
  float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
  float up = fabs(u), vp = fabs(v);
  float signed_distance = 1.0f - (up + vp);
  float d = fabs(signed_distance), r = 1.0f - d;
  float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * KASHA_PI / 4.0f;
  float z = copysign(1.0f - r * r, signed_distance);
  float cos_phi = copysign(cos(phi), u), sin_phi = copysign(sin(phi), v);
  float s = r * sqrt(fmax(0.0f, 2.0f - r * r));
  return (float3)(cos_phi * s, sin_phi * s, z);
}

inline float2 equal_area_to_square(float3 d) {
  float x = fabs(d.x), y = fabs(d.y), z = fabs(d.z);
  float r = sqrt(fmax(0.0f, 1.0f - z));
  float a = fmax(x, y), b = fmin(x, y);
  b = a == 0.0f ? 0.0f : b / a;
  float phi = atan(b) * 2.0f / KASHA_PI;
  if (x < y) phi = 1.0f - phi;
  float v = phi * r, u = r - v;
  if (d.z < 0.0f) {
    float t = u;
    u = 1.0f - v;
    v = 1.0f - t;
  }
  u = copysign(u, d.x);
  v = copysign(v, d.y);
  return (float2)(0.5f * (u + 1.0f), 0.5f * (v + 1.0f));
}

#endif
