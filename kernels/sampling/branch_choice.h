/* The choice of branch at a path vertex, shared by backward paths and photon mapping's camera
 * paths: gloss, passive or fluorescent in proportion to the energy each would bring to the film
 * under equal-energy light (docs/design.md#backward-transport); under a coat the Lambert parts'
 * energies take the coat's directional albedo factor (coat.h). */
#ifndef KASHA_BRANCH_CHOICE_H
#define KASHA_BRANCH_CHOICE_H

#include "materials/coat.h"
#include "film/path_weight.h"
#include "materials/surface.h"

/* Branch probabilities at a vertex, P_g, P_p, P_f, in proportion to the energy each brings to
 * the film under equal-energy light; they sum to 1 (absorption is left to Russian roulette). */
inline float3 branch_probabilities(const PathWeight* p, const FilmView* f, const Surface* surf) {
  float w0 = pw_energy(p, f, 0);
  if (!(w0 > 0.0f)) return (float3)(0.0f);
  float wg = surf->g * w0;
  float lambert = surface_lambert_albedo(surf);
  float wp = surf->passive ? pw_energy(p, f, surf->rho) * lambert : 0.0f;
#if KASHA_TRANSMISSION
  if (surf->share_t > 0.0f) wp += pw_energy(p, f, surf->tau);
#endif
  float wf = 0.0f;
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) wf = pw_energy(p, f, surf->ehat) * surf->a_sum * lambert;
#endif
  float total = wg + wp + wf;
  return total > 0.0f ? (float3)(wg, wp, wf) / total : (float3)(0.0f);
}

#endif
