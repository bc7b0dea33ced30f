/* Photons from the lights (docs/design.md#forward-transport): emission, and the one routine that decides what happens
 * at a hit — constant-energy branching by the branch energies under the photon's spectrum. The
 * caller decides what to do at the hit (splat to the camera, or store in the photon map).
 * A photon's spectrum is its power per bin (W). */
#ifndef KASHA_PHOTON_TRANSPORT_H
#define KASHA_PHOTON_TRANSPORT_H

#include "materials/coated_conductor.h"
#include "materials/gloss_lobe.h"
#include "lights/lights.h"
#include "materials/rough_interface.h"
#include "materials/metal_under_coat.h"
#include "sampling/roulette.h"
#include "sampling/sampler.h"
#include "sampling/sampling.h"
#include "geometry/scene_view.h"
#include "shared/spectral_product.h"
#include "materials/surface.h"
#include "materials/surface_at.h"
#include "materials/texture.h"
#include "media/medium.h"
#include "transport/medium_light.h"

typedef struct {
  float3 position;
  float3 direction;
  float start; /* the power it left its light with (W), Russian roulette's yardstick */
#if KASHA_DISPERSION
  int bin; /* the one bin it carries after a dispersive interface, -1 before */
#endif
#if KASHA_MEDIA
  int medium; /* the medium it travels in (media/medium.h), -1: vacuum */
#endif
  float power[KASHA_BINS];
} Photon;

inline float photon_total(const Photon* p) {
  float s = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) s += p->power[i];
  return s;
}

enum { BRANCH_ABSORBED = 0, BRANCH_GLOSS = 1, BRANCH_PASSIVE = 2, BRANCH_FLUORESCENT = 3, BRANCH_SPECULAR = 4 };

/* Where a photon left its light: the light's normal, its emitter, and the area density p_area
 * with which the point was chosen. */
typedef struct {
  float3 normal;
  int emitter;
  int tri; /* the emitting triangle it left (-1: a light that is not a triangle) */
  float area_pdf;
  float eps; /* how far off the light the photon starts (LightPoint::eps) */
#if KASHA_EMISSION_TEXTURES
  float scale; /* the emission texture's factor there */
#endif
#if KASHA_LIGHT_SOURCES
  const __global KLight* source; /* the light that is not a triangle it left, else null */
#endif
#if KASHA_MEDIUM_LIGHTS
  int medium; /* the emitting medium it started in (medium_light.h), -1: a light */
#endif
} LightOrigin;

/* Whether the photon started inside an emitting medium rather than at a light. */
inline bool origin_in_medium(const LightOrigin* o) {
#if KASHA_MEDIUM_LIGHTS
  return o->medium >= 0;
#else
  return false;
#endif
}

/* The scattering vertices a light path has at its start: a point of an emitting medium counts as
 * one, as pbrt-v4's volpath counts the collision that picks a medium's emission up against its
 * maxdepth (--max-depth), so every integrator caps the same paths. */
inline int origin_depth(const LightOrigin* o) { return origin_in_medium(o) ? 1 : 0; }

#if KASHA_MEDIUM_LIGHTS
/* A photon from a point of an emitting medium (medium_light.h), picked with u0 below the media's
 * share: a uniform direction, and power 4π E(x) V Δλ / (pick · photons), E what the medium emits
 * at x per unit length and solid angle and V its box's volume; 0 where x is not in the medium (the
 * caller passes such a photon over). The origin has no normal and no light. */
inline Photon emit_from_medium(const SceneView* s, float photons, float u0, float2 u, float2 d, LightOrigin* origin) {
  float rest;
  int m = medium_light_pick(s, u0, &rest);
  const __global KMedium* md = &s->media[m];
  Photon p;
  p.position = medium_light_point(md, (float3)(u.x, u.y, rest));
  p.direction = sample_uniform_sphere(d);
  p.medium = m;
#if KASHA_DISPERSION
  p.bin = -1;
#endif
  float scale = 4.0f * KASHA_PI * md->light_volume * s->bin_nm / (md->light_pick * photons);
  medium_emission_at(s, md, p.position, scale, p.power);
  p.start = photon_total(&p);
  /* The ray that finds the point's medium is traced only where the medium would emit there. */
  if (p.start > 0.0f && !medium_holds(s, m, p.position, p.direction)) {
    for (int i = 0; i < KASHA_BINS; ++i) p.power[i] = 0.0f;
    p.start = 0.0f;
  }
  origin->normal = (float3)(0.0f, 0.0f, 0.0f);
  origin->emitter = -1;
  origin->tri = -1;
  origin->area_pdf = 0.0f;
  origin->eps = 0.0f;
#if KASHA_LIGHT_SOURCES
  origin->source = 0;
#endif
#if KASHA_EMISSION_TEXTURES
  origin->scale = 1.0f;
#endif
  origin->medium = m;
  return p;
}
#endif

/* A photon leaving a light: a triangle chosen by power, a uniform point, a cosine-weighted
 * direction; its spectrum is the emitter's radiance scaled so that the `photons` of a pass carry
 * the lights' total power: Φ_i = Le_i Δλ · π / (p_area · photons). With `from_media` some start
 * in emitting media instead (emit_from_medium). */
inline Photon emit_photon(const SceneView* s, float photons, bool from_media, Sampler* sampler, LightOrigin* origin) {
  sampler_at(sampler, 0);
  float u0 = sample_2d(sampler).x;
  float2 u = sample_2d(sampler), d = sample_2d(sampler);
  float lights = 1.0f; /* the share of photons that leave the lights */
#if KASHA_MEDIUM_LIGHTS
  origin->medium = -1;
  /* With `from_media`, light paths start in emitting media by their share of the power; the
   * lights' densities (a source's pick, a triangle's p_area) take the rest's factor. */
  if (from_media) {
    float share = medium_light_share(s);
    if (u0 < share) return emit_from_medium(s, photons, u0, u, d, origin);
    lights = 1.0f - share;
    u0 = fmin((u0 - share) / lights, 0x1.fffffep-1f);
  }
#endif
  /* The light chosen by power: an emitting triangle, or (negative) a light that is not one. */
  int tri = s->light_tri[choose_light(s->light_cdf, s->light_count, u0)];
#if KASHA_LIGHT_SOURCES
  if (tri < 0) {
    /* A light that is not a triangle: no light point for forward to see (origin's normal 0). */
    const __global KLight* l = &s->lights[~tri];
    Photon p;
    int texel;
    float scale = emit_from_source(s, l, u, d, &p.position, &p.direction, &texel) * s->bin_nm / (lights * photons);
    origin->normal = (float3)(0.0f, 0.0f, 0.0f);
    origin->emitter = l->spectrum;
    origin->tri = -1;
    origin->area_pdf = 0.0f;
    origin->eps = 0.0f;
    origin->source = l;
#if KASHA_EMISSION_TEXTURES
    origin->scale = 1.0f;
#endif
    const __global float* le = emitter_spectrum(s, l->spectrum);
    for (int i = 0; i < KASHA_BINS; ++i) p.power[i] = le[i] * scale;
#if KASHA_ENVIRONMENT
    if (texel >= 0)
      for (int i = 0; i < KASHA_BINS; ++i) p.power[i] = env_radiance(s, l, texel, i) * scale;
#endif
    p.start = photon_total(&p);
#if KASHA_DISPERSION
    p.bin = -1;
#endif
#if KASHA_MEDIA
    p.medium = light_medium(s, -1, l);
#endif
    return p;
  }
#endif
  LightPoint lp = sample_light_on(s->tris, tri, u.x, u.y);
#if KASHA_EMISSION_TEXTURES
  /* sample_light_on's point is b1 = √u.x (1 − u.y), b2 = √u.x u.y on that triangle. */
  float texture_scale = emission_factor(s, tri, sqrt(u.x) * (1.0f - u.y), sqrt(u.x) * u.y);
#endif
  Photon p;
  p.position = lp.position;
  p.direction = sample_cosine_hemisphere(lp.normal, d.x, d.y);
  origin->normal = lp.normal;
  origin->emitter = lp.emitter;
  origin->tri = tri;
#if KASHA_LIGHT_SOURCES
  origin->source = 0;
#endif
  origin->area_pdf = s->emitter_area_pdf[lp.emitter] * lights;
  origin->eps = lp.eps;
  float scale = s->bin_nm * KASHA_PI / (origin->area_pdf * photons);
  const __global float* le = emitter_spectrum(s, lp.emitter);
#if KASHA_EMISSION_TEXTURES
  scale *= texture_scale;
  origin->scale = texture_scale;
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p.power[i] = le[i] * scale;
  p.start = photon_total(&p);
#if KASHA_DISPERSION
  p.bin = -1;
#endif
#if KASHA_MEDIA
  p.medium = light_medium(s, tri, 0);
#endif
  return p;
}

/* The medium the photon travels in (-1 without media). */
inline int photon_medium(const Photon* p) {
#if KASHA_MEDIA
  return p->medium;
#else
  return -1;
#endif
}

/* The medium of the connection from the photon's hit h towards `to` (media/medium.h). */
inline int photon_medium_towards(const SceneView* s, const Photon* p, const HitPoint* h, float3 to) {
#if KASHA_MEDIA
  return medium_after(s, h->tri, h->n, to, p->medium);
#else
  return -1;
#endif
}

/* The photon's next surface (intersect_surface); in a scene with media, through interfaces, its
 * power attenuated by the media on the way (media/medium.h). */
inline bool photon_intersect(const SceneView* s, Photon* p, HitPoint* h) {
#if KASHA_MEDIA
  MediaTrail trail;
  trail_clear(&trail);
  bool hit = intersect_through(s, p->position, p->direction, &p->medium, &trail, h);
  if (!trail_empty(&trail))
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= trail_transmittance(s, &trail, i);
  return hit;
#else
  return intersect_surface(s, p->position, p->direction, h);
#endif
}

/* Dimension pairs of the sampler: (light choice, —), the light point and the direction at the
 * light, then per hit (branch choice, roulette), the direction, and (the lobe's azimuth, —) drawn
 * only for a lobe; in a scene with scattering media a fourth, (the flight's bin, its distance) for
 * the flight that reaches the hit (photon_medium.h). */
#define PHOTON_PAIRS_AT_LIGHT 3
#if KASHA_SCATTERING
#define PHOTON_PAIRS_PER_HIT 4
#else
#define PHOTON_PAIRS_PER_HIT 3
#endif

/* Russian roulette (roulette.h) against the power the photon left its light with, from its
 * KASHA_PHOTON_ROULETTE_FROM-th hit on; false: it ends. */
inline bool photon_roulette(Photon* p, float u, int depth) {
  if (depth >= KASHA_PHOTON_ROULETTE_FROM) {
    float keep = roulette(photon_total(p) / p->start, u);
    if (keep == 0.0f) return false;
    if (keep != 1.0f)
      for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= keep;
  }
  return true;
}

/* A bin drawn in proportion to the photon's power in it (total: its sum, > 0), u uniform in
 * [0, 1): a dispersive interface's and a medium's free flight's choice. */
inline int photon_bin_by_power(const Photon* p, float u, float total) {
  float target = u * total, sum = 0.0f;
  int j = -1;
  for (int i = 0; i < KASHA_BINS; ++i) {
    if (p->power[i] <= 0.0f) continue;
    j = i;
    sum += p->power[i];
    if (sum > target) break;
  }
  return j;
}

#if KASHA_DISPERSION
/* At the photon's first dispersive interface: one bin j chosen in proportion to its power, u
 * uniform in [0, 1); the photon goes on with its whole power in that bin (Φ_j / p_j = ΣΦ).
 * -1 when it carries nothing. */
inline int photon_choose_bin(Photon* p, float u) {
  float total = photon_total(p);
  if (!(total > 0.0f)) return -1;
  int j = photon_bin_by_power(p, u, total);
  for (int i = 0; i < KASHA_BINS; ++i) p->power[i] = i == j ? total : 0.0f;
  return j;
}
#endif

#if KASHA_ROUGH
/* A photon at a rough interface (rough_interface.h): a direction drawn from the visible normals
 * seen from where it came, its power times f cos / pdf (flux: no 1/etap²) and, at a conductor,
 * F(λ); a dispersive dielectric first narrows it to one bin (u_bin). */
inline int scatter_rough(Photon* p, const Surface* s, float3 x, float3 n, float eps, float2 u_choice, float2 u_dir,
                         float u_bin, int depth) {
  float eta = 1.0f;
#if KASHA_DIELECTRIC
  eta = s->eta;
#endif
#if KASHA_DISPERSION
  if (s->dispersive) {
    if (p->bin < 0) p->bin = photon_choose_bin(p, u_bin);
    if (p->bin < 0) return BRANCH_ABSORBED;
    eta = s->eta_bins[p->bin];
  }
#endif
  Frame fr = surface_frame(s, n);
  float3 wo = to_local(&fr, -p->direction);
  InterfaceSample smp;
  bool ok = s->kind == KASHA_KIND_DIELECTRIC ? rough_dielectric_sample(wo, eta, s->alpha, false, u_choice.x, u_dir, &smp)
                                             : conductor_lobe_sample(s, wo, u_dir, &smp);
  if (!ok || !(smp.pdf > 0.0f)) return BRANCH_ABSORBED;
#if KASHA_CONDUCTOR
  if (s->kind == KASHA_KIND_CONDUCTOR)
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= conductor_reflectance(smp.cos_m, s->eta_c[i], s->k_c[i], s->coat_c);
#endif
  for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= smp.weight;
  p->direction = to_world(&fr, smp.wi);
  p->position = x + n * (smp.wi.z > 0.0f ? eps : -eps);
  return photon_roulette(p, u_choice.y, depth) ? BRANCH_SPECULAR : BRANCH_ABSORBED;
}
#endif

#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
/* A photon at a specular interface (surface_specular): a smooth dielectric reflects it with
 * probability F and refracts it otherwise, its power unchanged — flux, unlike radiance, carries
 * no 1/etap² — and a smooth conductor reflects it with power F(lambda)·Φ. */
inline int scatter_specular(Photon* p, const Surface* s, float3 x, float3 ns, bool front, float eps, float2 u_choice,
                            float2 u_dir, int depth) {
  float3 d = p->direction;
  float cos_i = -dot(d, ns);
  float side = eps;
#if KASHA_DIELECTRIC
  if (s->kind == KASHA_KIND_DIELECTRIC) {
    float eta = s->eta;
#if KASHA_DISPERSION
    if (s->dispersive) {
      if (p->bin < 0) p->bin = photon_choose_bin(p, u_dir.x);
      if (p->bin < 0) return BRANCH_ABSORBED;
      eta = s->eta_bins[p->bin];
    }
#endif
#if KASHA_THIN
    if (s->thin) {
      /* Reflects with R', else passes straight through (thin_dielectric_reflectance). */
      if (u_choice.x < thin_dielectric_reflectance(cos_i, eta))
        p->direction = reflect_dir(d, ns);
      else
        side = -eps;
      p->position = x + ns * side;
      return photon_roulette(p, u_choice.y, depth) ? BRANCH_SPECULAR : BRANCH_ABSORBED;
    }
#endif
    float etap = front ? eta : 1.0f / eta;
    if (u_choice.x < fresnel_dielectric(cos_i, etap)) {
      p->direction = reflect_dir(d, ns);
    } else {
      p->direction = refract_dir(d, ns, cos_i, etap);
      side = -eps;
    }
  }
#endif
#if KASHA_CONDUCTOR
  if (s->kind == KASHA_KIND_CONDUCTOR) {
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= conductor_reflectance(cos_i, s->eta_c[i], s->k_c[i], s->coat_c);
    p->direction = reflect_dir(d, ns);
  }
#endif
  p->position = x + ns * side;
  return photon_roulette(p, u_choice.y, depth) ? BRANCH_SPECULAR : BRANCH_ABSORBED;
}
#endif

/* The gloss branch's direction is chosen before the tabulated lobe: a mirror's, or a rough coat's
 * lobe's (sampled in scatter_gloss). */
inline bool gloss_direction_chosen(const Surface* s) {
#if KASHA_COATED
  return s->mirror || surface_coat_lobe(s);
#else
  return s->mirror;
#endif
}

/* The gloss branch of scatter_photon_about at normal ns: a mirror, a rough coat's GGX lobe (coat.h:
 * F G / G1 over the branch's probability, `per_pg` = sum / pg) or a tabulated lobe, the power
 * scaled by `k` = sum / total and the lobe's weight. False: the photon is absorbed. */
inline bool scatter_gloss(Photon* p, const Surface* s, const SceneView* scene, float3 ns, float k, float per_pg,
                          float2 u_dir, Sampler* sampler) {
  float3 d_in = p->direction;
  float3 mirror = reflect_dir(d_in, ns);
#if KASHA_COATED
  if (surface_coat_lobe(s)) {
    Frame fr = frame_of(ns);
    float3 wi;
    float weight, pdf;
    if (!coat_lobe_sample(s, to_local(&fr, -d_in), u_dir, &wi, &weight, &pdf)) return false;
    k = per_pg * weight;
    mirror = to_world(&fr, wi);
  }
#endif
  if (gloss_direction_chosen(s)) {
    p->direction = mirror;
  } else {
    float pdf;
    float3 wo = sample_lobe(s->m, scene->lobes, mirror, u_dir.x, u_dir.y, sample_2d(sampler).x, &pdf);
    float co = dot(wo, ns), ci = -dot(d_in, ns);
    if (co <= 0.0f) return false;
    k *= 2.0f * co / (ci + co);
    p->direction = wo;
  }
  for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= k;
  return true;
}

/* Scatters the photon at its depth-th hit x (ns: the normal on the side it arrived from, front:
 * that side is the front, eps: the hit's offset, HitPoint::eps).
 * Chooses gloss, passive or fluorescent re-emission with probability P_k / ΣP, P_g = g ΣΦ,
 * P_p = Σ ρ_i Φ_i, P_f = Σ a_i Φ_i; the new spectrum (g Φ, ρ∘Φ or ê (a·Φ)) is divided by that
 * probability, so the photon's power becomes ΣP; then Russian roulette (roulette.h) against the
 * power it left its light with. Returns the branch. */
inline int scatter_photon_about(Photon* p, const Surface* s, const SceneView* scene, float3 x, float3 ns, bool front,
                                float eps, Sampler* sampler, int depth) {
  sampler_at(sampler, PHOTON_PAIRS_AT_LIGHT + depth * PHOTON_PAIRS_PER_HIT);
  float2 u_choice = sample_2d(sampler), u_dir = sample_2d(sampler);
#if KASHA_ROUGH
  if (surface_rough(s)) return scatter_rough(p, s, x, front ? ns : -ns, eps, u_choice, u_dir, sample_2d(sampler).x, depth);
#endif
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
  if (surface_specular(s)) return scatter_specular(p, s, x, ns, front, eps, u_choice, u_dir, depth);
#endif
  float total = photon_total(p);
  float pg = s->g * total, pp = 0.0f, pf = 0.0f;
  if (s->passive) pp = spectrum_dot(KASHA_BINS, p->power, s->rho, 0);
  float pt = 0.0f; /* τ's share: through a transmitting surface (surface.h) */
#if KASHA_TRANSMISSION
  if (s->share_t > 0.0f) pt = spectrum_dot(KASHA_BINS, p->power, s->tau, 0);
#endif
#if KASHA_FLUORESCENCE
  if (s->fluorescent) pf = spectrum_dot(KASHA_BINS, p->power, s->a, 0);
#endif
#if KASHA_COATED
  /* Under a coat the Lambert parts take t(θi) τ̄ / η² on the way (coat.h). */
  pp *= surface_lambert_albedo(s);
  pf *= surface_lambert_albedo(s);
#endif
  float sum = pg + pp + pt + pf;
  if (!(sum > 0.0f)) return BRANCH_ABSORBED;
  float xi = u_choice.x * sum;
  float3 d_in = p->direction;
  int branch;
  if (xi < pg) {
    if (!scatter_gloss(p, s, scene, ns, sum / total, sum / pg, u_dir, sampler)) return BRANCH_ABSORBED;
    branch = BRANCH_GLOSS;
  } else if (xi < pg + pp || (pf <= 0.0f && pt <= 0.0f)) {
    float k = sum / pp;
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= s->rho[i] * k;
    p->direction = sample_cosine_hemisphere(ns, u_dir.x, u_dir.y);
    branch = BRANCH_PASSIVE;
#if KASHA_TRANSMISSION
  } else if (xi < pg + pp + pt || pf <= 0.0f) {
    float k = sum / pt;
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= s->tau[i] * k;
    p->direction = sample_cosine_hemisphere(-ns, u_dir.x, u_dir.y);
    branch = BRANCH_PASSIVE;
#endif
#if KASHA_FLUORESCENCE
  } else {
    /* The photon changes colour: its power re-emitted with the emission spectrum. */
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] = s->ehat[i] * sum;
#if KASHA_DISPERSION
    p->bin = -1;
#endif
    p->direction = sample_cosine_hemisphere(ns, u_dir.x, u_dir.y);
    branch = BRANCH_FLUORESCENT;
#endif
  }
#if KASHA_COATED
  /* Under a coat f carries t(θi) t(θo) / η² more. The passive branch divided by its probability
   * (which took the albedo factor L = t(θi) τ̄ / η²); the fluorescent one's ê (a·Φ) / P_f left L
   * out, so it divides by it here. */
  if (s->coated && branch != BRANCH_GLOSS) {
    float k = surface_lambert_weight(s, dot(p->direction, ns));
    if (branch == BRANCH_FLUORESCENT) k /= surface_lambert_albedo(s);
    for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= k;
  }
#endif
#if KASHA_TRANSMISSION
  /* Off the side the photon leaves by: the far one after a transmission. */
  if (dot(p->direction, ns) < 0.0f) ns = -ns;
#endif
  p->position = x + ns * eps;
  return photon_roulette(p, u_choice.y, depth) ? branch : BRANCH_ABSORBED;
}

/* Scatters the photon at its depth-th hit h (scatter_photon_about its normal). With shading
 * normals a new direction that would leak through the geometric surface ends the photon, and its
 * power takes Veach's correction for flux (adjoint) transport through a shading normal,
 * |wi·ns| |wo·ng| / (|wi·ng| |wo·ns|) for arrival wi and departure wo, so that light tracing and
 * photon mapping agree with camera paths; the new ray leaves off the geometric surface. */
inline int scatter_photon_at(Photon* p, const Surface* s, const SceneView* scene, const HitPoint* h, Sampler* sampler,
                             int depth) {
#if KASHA_SHADING_NORMALS
  float3 d_in = p->direction;
  int branch = scatter_photon_about(p, s, scene, h->x, h->ns, h->front, h->eps, sampler, depth);
  if (branch == BRANCH_ABSORBED) return branch;
  float3 d = p->direction;
  if (!hit_no_leak(h, d)) return BRANCH_ABSORBED;
  float k = fabs(dot(d_in, h->ns) * dot(d, h->ng)) / fabs(dot(d_in, h->ng) * dot(d, h->ns));
  if (!(k < INFINITY)) return BRANCH_ABSORBED;
  for (int i = 0; i < KASHA_BINS; ++i) p->power[i] *= k;
  p->position = h->x + h->ng * (dot(d, h->ng) > 0.0f ? h->eps : -h->eps);
  return branch;
#else
  return scatter_photon_about(p, s, scene, h->x, h->ns, h->front, h->eps, sampler, depth);
#endif
}

/* scatter_photon_at, the photon then in the medium its new direction leaves into. */
inline int scatter_photon(Photon* p, const Surface* s, const SceneView* scene, const HitPoint* h, Sampler* sampler,
                          int depth) {
  int branch = scatter_photon_at(p, s, scene, h, sampler, depth);
#if KASHA_MEDIA
  if (branch != BRANCH_ABSORBED) p->medium = medium_after(scene, h->tri, h->n, p->direction, p->medium);
#endif
  return branch;
}

/* Light arriving along d and followed as flux (a photon stored, or connected to the camera) meets
 * a Lambert or gloss part through the shading normal: |d·ns| / |d·ng| (the arrival half of
 * Veach's correction); 1 without shading normals. */
inline float photon_arrival_correction(const HitPoint* h, float3 d) {
#if KASHA_SHADING_NORMALS
  float k = fabs(dot(d, h->ns)) / fabs(dot(d, h->ng));
  return k < INFINITY ? k : 0.0f;
#else
  return 1.0f;
#endif
}

#endif
