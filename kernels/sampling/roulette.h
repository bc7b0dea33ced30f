/* Russian roulette for camera paths and photons: the first vertices never end a path (branch
 * choices there always scatter, with the albedo in the weight); from vertex
 * KASHA_CAMERA_ROULETTE_FROM (camera paths) or KASHA_PHOTON_ROULETTE_FROM (photons) on a path
 * carrying a fraction `ratio` of what it started with survives with probability min(1, ratio) and
 * is scaled up by its inverse, so the estimate stays unbiased and paths that carry little end
 * early. Camera paths start at their fourth vertex, photons at their second hit: measured at equal
 * time, later roulette pays for camera paths (lower variance per path for a little more work) but
 * not for photons, which light tracing splats at every hit anyway. */
#ifndef KASHA_ROULETTE_H
#define KASHA_ROULETTE_H

#define KASHA_CAMERA_ROULETTE_FROM 3
#define KASHA_PHOTON_ROULETTE_FROM 1

/* The factor a surviving path is scaled by, or 0 when it ends (u uniform in [0, 1)). Callers test
 * the depth first, so earlier vertices do not compute the ratio. */
inline float roulette(float ratio, float u) {
  float survive = fmin(1.0f, ratio);
  return u < survive ? 1.0f / survive : 0.0f;
}

#endif
