/* Sampling the Henyey–Greenstein phase function (shared/hg_phase.h, pbrt-v4's convention): sampling
 * it exactly makes a scattering's weight 1. */
#ifndef KASHA_PHASE_H
#define KASHA_PHASE_H

#include "sampling/sampling.h"
#include "shared/hg_phase.h"

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
