/* The factor K of a photon-mapping visible point (docs/design.md#photon-mapping), shared by host and kernels: it maps
 * the power of a photon arriving there to the pixel's film rows,
 *     K = C∘d + c bᵀ     (d: N values; c: R values and b: N values in a fluorescent scene only),
 * stored in the visible-point record of photon_layout.h. vf_build makes it from a camera path's
 * diagonal weight w and the surface's spectra; vf_apply gives K·Φ for a photon's spectrum Φ. */
#ifndef KASHA_VERTEX_FACTOR_H
#define KASHA_VERTEX_FACTOR_H

#include "shared/photon_layout.h"
#include "shared/spectral_product.h"

#ifndef __OPENCL_VERSION__
namespace kasha {
#endif

/* The film the factor serves: bins N, rows R, whether rows are bins, and C for an XYZ film. */
typedef struct {
  int bins, rows, spectral, fluorescent;
  const KASHA_GLOBAL float* cmf;
} VertexFactorLayout;

/* K for a Lambert vertex reached with weight w, scaled by k (1/π over the branch probability):
 * d = k w∘ρ, c = k C(w∘ê), b = a. */
inline void vf_build(VertexFactorLayout L, KASHA_GLOBAL float* vp, const float* w, const KASHA_GLOBAL float* rho,
                     const KASHA_GLOBAL float* ehat, const KASHA_GLOBAL float* a, float k) {
  for (int i = 0; i < L.bins; ++i) vp[KASHA_VP_D + i] = w[i] * rho[i] * k;
  if (!L.fluorescent) return;
  for (int r = 0; r < L.rows; ++r)
    vp[KASHA_VP_C(L.bins) + r] = (float)(k * film_row(L.cmf, L.spectral, L.bins, r, w, ehat, 0));
  for (int i = 0; i < L.bins; ++i) vp[KASHA_VP_B(L.bins, L.rows) + i] = a[i];
}

/* K for a collision in a medium (shared/volume_gather.h): its elastic branch, d = k w∘σs and no
 * c bᵀ, or (sigma_s null) one dye's re-emission, c = k C(w∘ê), b = a and no d. */
inline void vf_build_medium(VertexFactorLayout L, KASHA_GLOBAL float* vp, const float* w,
                            const KASHA_GLOBAL float* sigma_s, const KASHA_GLOBAL float* ehat,
                            const KASHA_GLOBAL float* a, float k) {
  for (int i = 0; i < L.bins; ++i) vp[KASHA_VP_D + i] = sigma_s ? w[i] * sigma_s[i] * k : 0.0f;
  if (!L.fluorescent) return;
  for (int r = 0; r < L.rows; ++r)
    vp[KASHA_VP_C(L.bins) + r] = sigma_s ? 0.0f : (float)(k * film_row(L.cmf, L.spectral, L.bins, r, w, ehat, 0));
  for (int i = 0; i < L.bins; ++i) vp[KASHA_VP_B(L.bins, L.rows) + i] = sigma_s ? 0.0f : a[i];
}

/* rows += scale · K·Φ */
inline void vf_apply_scaled(VertexFactorLayout L, const KASHA_GLOBAL float* vp, const KASHA_GLOBAL float* phi,
                            kasha_real scale, kasha_real* rows) {
  film_rows_add(L.cmf, L.spectral, L.bins, 0, vp + KASHA_VP_D, phi, scale, rows);
  if (!L.fluorescent) return;
  kasha_real bphi = scale * spectrum_dot(L.bins, 0, vp + KASHA_VP_B(L.bins, L.rows), phi);
  for (int r = 0; r < L.rows; ++r) rows[r] += vp[KASHA_VP_C(L.bins) + r] * bphi;
}

inline void vf_apply(VertexFactorLayout L, const KASHA_GLOBAL float* vp, const KASHA_GLOBAL float* phi,
                     kasha_real* rows) {
  vf_apply_scaled(L, vp, phi, 1, rows);
}

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
