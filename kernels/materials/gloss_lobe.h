/* The white near-specular gloss lobe: p(delta), a density per solid angle of the angle delta from
 * the mirror direction, zero outside the cone, tabulated in KASHA_LOBE_CELLS equal rings of angle
 * (piecewise constant; table: pdf per ring, then the CDF over rings). The BRDF is
 *   f_g(wo, wi) = g p(delta) * 2 / (|cos wi| + |cos wo|),
 * reciprocal, and with a sampling weight (f cos / pdf) of at most g on average over the lobe.
 * An ideal mirror (lobe == -1) is the delta limit: weight exactly g. */
#ifndef KASHA_GLOSS_LOBE_H
#define KASHA_GLOSS_LOBE_H

#include "sampling/sampling.h"
#include "shared/shared_types.h"

inline float lobe_pdf(const __global KMaterial* m, const __global float* lobes, float cos_delta) {
  float delta = acos(clamp(cos_delta, -1.0f, 1.0f));
  if (delta >= m->cone_rad) return 0.0f;
  int cell = min((int)(delta / m->cone_rad * KASHA_LOBE_CELLS), KASHA_LOBE_CELLS - 1);
  return lobes[m->lobe + cell];
}

/* A direction about `mirror` drawn from the lobe; returns its pdf per solid angle. */
inline float3 sample_lobe(const __global KMaterial* m, const __global float* lobes, float3 mirror, float u1,
                          float u2, float u3, float* pdf) {
  const __global float* cdf = lobes + m->lobe + KASHA_LOBE_CELLS;
  int lo = 0, hi = KASHA_LOBE_CELLS - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (cdf[mid] > u1) hi = mid;
    else lo = mid + 1;
  }
  float width = m->cone_rad / KASHA_LOBE_CELLS;
  /* Uniform in solid angle within the ring: cos(delta) uniform between the ring's edges. */
  float c0 = cos(lo * width), c1 = cos((lo + 1) * width);
  float cos_delta = c0 + u2 * (c1 - c0);
  float sin_delta = sqrt(fmax(0.0f, 1.0f - cos_delta * cos_delta));
  float phi = 2.0f * KASHA_PI * u3;
  float3 s, t;
  basis_around(mirror, &s, &t);
  *pdf = lobes[m->lobe + lo];
  return normalize(sin_delta * cos(phi) * s + sin_delta * sin(phi) * t + cos_delta * mirror);
}

/* f_g without g: p(delta) * 2 / (cos_i + cos_o), cosines about the shading side's normal. */
inline float lobe_brdf(const __global KMaterial* m, const __global float* lobes, float3 wo, float3 wi, float3 n) {
  float ci = dot(wi, n), co = dot(wo, n);
  if (ci <= 0.0f || co <= 0.0f) return 0.0f;
  float3 mirror = reflect_dir(-wo, n);
  return lobe_pdf(m, lobes, dot(wi, mirror)) * 2.0f / (ci + co);
}

#endif
