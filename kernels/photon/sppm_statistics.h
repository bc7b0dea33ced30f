/* The per-pixel statistics of stochastic progressive photon mapping (Hachisuka & Jensen 2009):
 * radius R, photon count n and shrunk flux τ (R values, one per film row). After a pass that found
 * m photons with flux φ inside R:
 *     n' = n + αm,  R' = R·sqrt(n'/(n + m)),  τ' = (τ + φ)·R'²/R²,
 * and after k passes the radiance is τ/(k·π·R²·Δλ). */
#ifndef KASHA_SPPM_STATISTICS_H
#define KASHA_SPPM_STATISTICS_H

/* One pass's gather (m photons, flux φ·scale) into a pixel's statistics; a pass that found
 * nothing leaves them as they are. */
inline void sppm_add_pass(__global float* radius, __global float* count, __global float* tau, int rows,
                          const __global float* phi, float scale, int m, float alpha) {
  if (m <= 0) return;
  float n = *count, n_new = n + alpha * m;
  float shrink = n_new / (n + m);
  for (int k = 0; k < rows; ++k) tau[k] = (tau[k] + phi[k] * scale) * shrink;
  *count = n_new;
  *radius *= sqrt(shrink);
}

/* Radiance per nm of the k-th row after `passes` passes (0 before a radius). */
inline float sppm_radiance(float radius, const __global float* tau, int k, float passes, float bin_nm) {
  float area = passes * KASHA_PI * radius * radius * bin_nm;
  return area > 0.0f ? tau[k] / area : 0.0f;
}

#endif
