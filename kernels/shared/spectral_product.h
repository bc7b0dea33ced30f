/* Products of spectra and the film's rows, shared by host and kernels (the host gather of photon
 * mapping uses them too). The film's rows over the N bins are C: x̄ȳz̄ times the bin width for an
 * XYZ film (3 rows, `cmf` is 3 × N), the identity for a spectral film (N rows). Any of the
 * factors x (private), y, z (global) may be null, standing for a spectrum of ones. */
#ifndef KASHA_SPECTRAL_PRODUCT_H
#define KASHA_SPECTRAL_PRODUCT_H

#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
namespace kasha {
#endif

/* Σ_i x_i y_i z_i */
inline kasha_real spectrum_dot(int bins, const float* x, const KASHA_GLOBAL float* y,
                               const KASHA_GLOBAL float* z) {
  kasha_real s = 0;
  for (int i = 0; i < bins; ++i)
    s += (kasha_real)(x ? x[i] : 1.0f) * (y ? y[i] : 1.0f) * (z ? z[i] : 1.0f);
  return s;
}

/* Film row r of the product: Σ_i C_ri x_i y_i z_i (one term on a spectral film). */
inline kasha_real film_row(const KASHA_GLOBAL float* cmf, int spectral, int bins, int r, const float* x,
                           const KASHA_GLOBAL float* y, const KASHA_GLOBAL float* z) {
  if (spectral) return (kasha_real)(x ? x[r] : 1.0f) * (y ? y[r] : 1.0f) * (z ? z[r] : 1.0f);
  kasha_real s = 0;
  for (int i = 0; i < bins; ++i)
    s += (kasha_real)cmf[r * bins + i] * (x ? x[i] : 1.0f) * (y ? y[i] : 1.0f) * (z ? z[i] : 1.0f);
  return s;
}

/* rows[r] += scale · Σ_i C_ri x_i y_i z_i for every film row. */
inline void film_rows_add(const KASHA_GLOBAL float* cmf, int spectral, int bins, const float* x,
                          const KASHA_GLOBAL float* y, const KASHA_GLOBAL float* z, kasha_real scale,
                          kasha_real* rows) {
  if (spectral) {
    for (int i = 0; i < bins; ++i) rows[i] += scale * (x ? x[i] : 1.0f) * (y ? y[i] : 1.0f) * (z ? z[i] : 1.0f);
    return;
  }
  for (int i = 0; i < bins; ++i) {
    kasha_real v = scale * (x ? x[i] : 1.0f) * (y ? y[i] : 1.0f) * (z ? z[i] : 1.0f);
    rows[0] += cmf[i] * v;
    rows[1] += cmf[bins + i] * v;
    rows[2] += cmf[2 * bins + i] * v;
  }
}

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
