/* Photons gathered in a participating medium (docs/media.md#what-each-integrator-does): point-to-point
 * volumetric merging, shared by the device's gather (photon_gather.cl) and the host's
 * (photon_host_gather.cpp). A photon stored at a collision in a medium counts at a visible point at
 * a collision within the radius r, in 3-D, and only there; surface photons and surface visible
 * points keep to each other (photon_layout.h: a record in a medium has no normal).
 *
 * SPPM's statistics divide a pixel's flux by the disc πr² (sppm_radiance); a sphere's (4/3)πr³
 * differs by 3/(4r), which the gather applies at the radius it gathers within, so that a pixel
 * whose visible point is on a surface in one pass and in a medium in another keeps one set of
 * statistics: a pass's flux gathered within r_i is kept scaled by (r/r_i)² as the radius shrinks
 * to r and divided by πr² in the image, so by (4/3)πr_i³ in all — what a sphere's own
 * progressive update gives. */
#ifndef KASHA_VOLUME_GATHER_H
#define KASHA_VOLUME_GATHER_H

#include "shared/hg_phase.h"
#include "shared/photon_layout.h"
#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
namespace kasha {
#endif

/* Whether a photon or visible-point record lies at a collision in a medium: it has no normal. */
inline int record_in_medium(const KASHA_GLOBAL float* r) {
  return r[3] == 0.0f && r[4] == 0.0f && r[5] == 0.0f;
}

/* The factor of photon ph at the medium's visible point vp (record layouts of photon_layout.h for
 * N bins, R rows, fluorescent or not) gathered within r: the phase function between the visible
 * point's ωo and the direction the photon came from, p(ωo, −ω_photon; g), times 3/(4r). A
 * re-emitting visible point holds g = 0: isotropic. */
inline float volume_gather_weight(const KASHA_GLOBAL float* vp, const KASHA_GLOBAL float* ph, int bins, int rows,
                                  int fluorescent, float r) {
  const KASHA_GLOBAL float* wo = vp + KASHA_VP_WO(bins, rows, fluorescent);
  const KASHA_GLOBAL float* d = ph + KASHA_PHOTON_DIRECTION(bins);
  float cos_t = -(wo[0] * d[0] + wo[1] * d[1] + wo[2] * d[2]);
  return hg_phase(cos_t, vp[KASHA_VP_G(bins, rows, fluorescent)]) * 0.75f / r;
}

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
