/* The Henyey–Greenstein phase function (docs/media.md#scattering), shared by host and kernels (the
 * host's gather of photons in media evaluates it too), in pbrt-v4's convention: ωo points back
 * along the path, ωi onward, and the value depends on cos = ωo·ωi, so forward scattering (g > 0)
 * peaks at ωi = −ωo. It integrates to 1 over the sphere. */
#ifndef KASHA_HG_PHASE_H
#define KASHA_HG_PHASE_H

#ifndef __OPENCL_VERSION__
#include <cmath>
namespace kasha {
#endif

inline float hg_phase(float cos_t, float g) {
  float denom = 1.0f + g * g + 2.0f * g * cos_t;
  return 0.07957747154594767f /* 1/4π */ * (1.0f - g * g) / (denom * (float)sqrt(denom));
}

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
