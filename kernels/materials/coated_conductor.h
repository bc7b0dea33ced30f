/* A conductor's reflectance, bare or under a smooth clear coat (pbrt-v4's coatedconductor with
 * both interfaces smooth and albedo 0; docs/materials.md#coated-conductors). With both smooth,
 * every path through the layer stays on the one mirror direction, so pbrt-v4's random walk sums
 * to a geometric series: with F = F(θ, η) the coat's reflectance (the same from either side at
 * θ and θt), Fc the conductor's at θt with index (n + ik) / η, and A = exp(−2d / cos θt) the
 * layer's transmittance down and up,
 *     R(θ) = F + (1 − F)² Fc A / (1 − F Fc A).
 * pbrt-v4's walk stops at maxdepth (10 scattering events: 5 at the metal), which drops the
 * series' terms past (F Fc A)^4: a share (F Fc A)^5 of the metal's part: below 1e-5 up to 60° at
 * η 1.5, under 1 % at 80°. kasha sums them all.
 * A rough layered metal's metal part (coat.z = 1, materials/metal_under_coat.h) is seen through
 * its coat, whose factors that lobe carries: here only the metal's own Fresnel reflectance under
 * the coat, index (n + ik) / η, at the facet's cosine inside, times the part's layer_scale.
 * Defines: KASHA_COATED (0: no coat anywhere, and this is fresnel_conductor). */
#ifndef KASHA_COATED_CONDUCTOR_H
#define KASHA_COATED_CONDUCTOR_H

#include "materials/fresnel.h"

#ifndef KASHA_COATED
#define KASHA_COATED 0
#endif

/* coat: (the coat's index over the outside's, its optical depth along the normal, under_coat,
 * layer_scale); index 0: a bare conductor. eta, k: the conductor's index over the outside's. */
inline float conductor_reflectance(float cos_i, float eta, float k, float4 coat) {
#if KASHA_COATED
  if (coat.z > 0.0f) return coat.w * fresnel_conductor(clamp(cos_i, 0.0f, 1.0f), eta / coat.x, k / coat.x);
  if (coat.x > 0.0f) {
    float ci = clamp(cos_i, 0.0f, 1.0f);
    float F = fresnel_dielectric(ci, coat.x);
    if (F >= 1.0f) return 1.0f; /* grazing, or total reflection off a coat below the outside's index */
    float cos_t = sqrt(fmax(0.0f, 1.0f - (1.0f - ci * ci) / (coat.x * coat.x)));
    float fc = fresnel_conductor(cos_t, eta / coat.x, k / coat.x);
    if (coat.y > 0.0f) fc *= cos_t > 0.0f ? exp(-2.0f * coat.y / cos_t) : 0.0f;
    return F + (1.0f - F) * (1.0f - F) * fc / (1.0f - F * fc);
  }
#endif
  return fresnel_conductor(cos_i, eta, k);
}

#endif
