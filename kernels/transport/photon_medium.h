/* Photons in scattering and fluorescent media (docs/media.md#what-each-integrator-does): their
 * flight, and what a collision does to them. Light tracing (forward.cl) and photon mapping
 * (photon_map.cl) share it, as they share photon_transport.h's surface branches.
 *
 * The flight is the camera paths' (medium_flight.h) with the photon's power as the energy: a bin j
 * drawn by its share c_j = Φ_j / ΣΦ, the distance by bin j's optical depth, and each bin weighed by
 * its density over the mixture's — at a collision in medium m Φ_i ← Φ_i T_i / Σ_k c_k σt_k T_k,
 * on reaching a surface Φ_i ← Φ_i T_i / Σ_k c_k T_k. At a collision the photon is scattered
 * (Φ∘σs, a Henyey–Greenstein direction) or re-emitted by one of the medium's dyes (ê Φ_d (a·Φ),
 * isotropic), chosen with constant energy as at a surface: the branch's power over its share. */
#ifndef KASHA_PHOTON_MEDIUM_H
#define KASHA_PHOTON_MEDIUM_H

#include "film/film_view.h"
#include "media/phase.h"
#include "sampling/sampling.h"
#include "transport/medium_flight.h"
#include "transport/photon_transport.h"

#if KASHA_SCATTERING
/* The sampler pair a photon's flight to its depth-th hit draws from (after the hit's own pairs). */
#define PHOTON_FLIGHT_PAIR 3

/* Φ ← Φ∘T / Σ_k c_k u_k over the trail (u_k = σt_k(m) T_k at a collision in m ≥ 0, T_k on reaching a
 * surface), c_k = Φ_k / total the shares before the flight; returns T̄, the mean of T over the bins. */
inline float photon_flight_weight(Photon* p, const SceneView* s, const MediaTrail* t, int m, float total) {
  float den = 0.0f, tr[KASHA_BINS];
  float tbar = trail_bins(s, t, tr);
  const __global float* sigma_t = m >= 0 ? medium_extinction(s, &s->media[m]) : 0;
  for (int k = 0; k < KASHA_BINS; ++k)
    if (p->power[k] > 0.0f) den += p->power[k] * tr[k] * (sigma_t ? sigma_t[k] : 1.0f);
  float scale = den > 0.0f ? total / den : 0.0f;
  for (int k = 0; k < KASHA_BINS; ++k) p->power[k] *= tr[k] * scale;
  return tbar;
}

/* The photon's flight from its position (photon_intersect's, with collisions): KASHA_FLIGHT_SURFACE
 * with the hit h, KASHA_FLIGHT_SCATTERED with h->x the collision in p->medium, or
 * KASHA_FLIGHT_ESCAPED; *tbar the mean over the bins of its transmittance (1 where it carried
 * nothing). The flight's pair is its depth-th hit's. */
inline int photon_flight(Photon* p, const SceneView* s, Sampler* sampler, int depth, HitPoint* h, float* tbar) {
  sampler_at(sampler, PHOTON_PAIRS_AT_LIGHT + depth * PHOTON_PAIRS_PER_HIT + PHOTON_FLIGHT_PAIR);
  float2 u = sample_2d(sampler);
  float total = photon_total(p);
  MediaTrail trail;
  *tbar = 1.0f;
  if (!(total > 0.0f)) return KASHA_FLIGHT_ESCAPED;
  int j = photon_bin_by_power(p, u.x, total);
  int reached = flight_walk(s, p->position, p->direction, &p->medium, j, flight_depth(u.y), &trail, h);
  if (reached == KASHA_FLIGHT_SCATTERED) collision_coefficients(s, p->medium, h->x);
  *tbar = photon_flight_weight(p, s, &trail, reached == KASHA_FLIGHT_SCATTERED ? p->medium : -1, total);
  return reached;
}

/* rows += scale · what the photon's collision in its medium m sends along `to` (away from it),
 * through a connection of transmittance tr (null: 1): Φ∘σs times the phase function, and each
 * dye's ê Φ_d (a·Φ) / 4π. Light tracing's splat of a collision, forward's and vcm's. */
inline void collision_film_rows(const SceneView* s, const FilmView* f, const __global KMedium* m, const Photon* p,
                                float3 to, const __global float* tr, float scale, float* rows) {
  film_rows(f, p->power, medium_scattering(s, m), tr,
            scale * hg_phase(dot(to, -p->direction), m->g), rows);
#if KASHA_FLUORESCENCE
  for (int d = 0; d < m->fluorophores; ++d) {
    const __global KFluorophore* fl = &m->fluorophore[d];
    float emitted = fl->yield * spectrum_dot(KASHA_BINS, p->power, s->spectra + fl->absorption, 0);
    film_rows(f, 0, s->spectra + fl->emission, tr, emitted * KASHA_INV_4PI * scale, rows);
  }
#endif
}

/* The power each branch of a collision in medium m carries on: [0] elastic, Σ σs_i Φ_i; [1 + k]
 * dye k's re-emission, Φ_k Σ a_i Φ_i (ê sums to 1). Returns their sum. */
inline float photon_medium_branches(const Photon* p, const SceneView* s, const __global KMedium* m, float* power) {
  float sum = power[0] = spectrum_dot(KASHA_BINS, p->power, medium_scattering(s, m), 0);
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) {
    const __global KFluorophore* fl = &m->fluorophore[k];
    power[1 + k] = fl->yield * spectrum_dot(KASHA_BINS, p->power, s->spectra + fl->absorption, 0);
    sum += power[1 + k];
  }
#endif
  return sum;
}

/* A collision at x in the photon's medium, its depth-th hit: a branch by the power it carries on
 * (u_choice.x), the new power that branch's over its share (so ΣΦ becomes the branches' sum), a
 * direction, and Russian roulette. Returns BRANCH_PASSIVE (elastic), BRANCH_FLUORESCENT or
 * BRANCH_ABSORBED. */
inline int scatter_photon_in_medium(Photon* p, const SceneView* s, float3 x, Sampler* sampler, int depth) {
  sampler_at(sampler, PHOTON_PAIRS_AT_LIGHT + depth * PHOTON_PAIRS_PER_HIT);
  float2 u_choice = sample_2d(sampler), u_dir = sample_2d(sampler);
  const __global KMedium* m = &s->media[p->medium];
  float power[1 + KASHA_MEDIUM_FLUOROPHORES];
  float sum = photon_medium_branches(p, s, m, power);
  if (!(sum > 0.0f)) return BRANCH_ABSORBED;
  int branch = medium_branch(power, m->fluorophores, u_choice.x * sum);
  if (!(power[branch] > 0.0f)) return BRANCH_ABSORBED;
  float k = sum / power[branch];
  p->position = x;
  if (branch == 0) {
    float pdf;
    const __global float* sigma_s = medium_scattering(s, m);
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= sigma_s[i] * k;
    p->direction = hg_sample(-p->direction, m->g, u_dir, &pdf);
  }
#if KASHA_FLUORESCENCE
  else {
    /* The photon changes colour: the dye's share re-emitted with its emission spectrum. */
    const __global float* e = s->spectra + m->fluorophore[branch - 1].emission;
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] = e[i] * sum;
    p->direction = sample_uniform_sphere(u_dir);
#if KASHA_DISPERSION
    p->bin = -1;
#endif
  }
#endif
  if (!photon_roulette(p, u_choice.y, depth)) return BRANCH_ABSORBED;
  return branch == 0 ? BRANCH_PASSIVE : BRANCH_FLUORESCENT;
}
#endif

#endif
