/* The Henyey–Greenstein phase function (docs/media.md#scattering), in pbrt-v4's convention: wo
 * points back along the path, wi onward, and the value depends on cos = wo·wi, so forward
 * scattering (g > 0) peaks at wi = −wo. It integrates to 1 over the sphere, and sampling it
 * exactly makes a scattering's weight 1. */
#ifndef KASHA_PHASE_H
#define KASHA_PHASE_H

#include "sampling/sampling.h"

inline float hg_phase(float cos_t, float g) {
  float denom = 1.0f + g * g + 2.0f * g * cos_t;
  return KASHA_INV_4PI * (1.0f - g * g) / (denom * sqrt(denom));
}

/* A direction wi drawn with density hg_phase(wo·wi, g) per solid angle (pbrt-v4's
 * SampleHenyeyGreenstein), *pdf that density. */
inline float3 hg_sample(float3 wo, float g, float2 u, float* pdf) {
  float cos_t;
  if (fabs(g) < 1e-3f) {
    cos_t = 1.0f - 2.0f * u.x;
  } else {
    float q = (1.0f - g * g) / (1.0f + g - 2.0f * g * u.x);
    cos_t = -1.0f / (2.0f * g) * (1.0f + g * g - q * q);
  }
  cos_t = clamp(cos_t, -1.0f, 1.0f);
  float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t)), phi = 2.0f * KASHA_PI * u.y;
  float3 s, t;
  basis_around(wo, &s, &t);
  *pdf = hg_phase(cos_t, g);
  return normalize(sin_t * cos(phi) * s + sin_t * sin(phi) * t + cos_t * wo);
}

#endif
