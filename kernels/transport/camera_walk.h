/* The camera walk backward (backward.cl) and photon mapping's camera pass (photon_map.cl) share, so
 * both weigh emission, next-event estimation and gloss bounces alike on the same sample dimensions;
 * each kernel keeps only what it does at a Lambert part (backward scatters on, photon mapping stops). */
#ifndef KASHA_CAMERA_WALK_H
#define KASHA_CAMERA_WALK_H

#include "sampling/branch_choice.h"
#include "film/film_view.h"
#include "materials/gloss_lobe.h"
#include "geometry/hit_point.h"
#include "materials/hit_material.h"
#include "lights/lights.h"
#include "lights/next_event.h"
#include "film/path_weight.h"
#include "materials/rough_interface.h"
#include "materials/metal_under_coat.h"
#include "sampling/roulette.h"
#include "sampling/sampler.h"
#include "geometry/scene_view.h"
#include "materials/surface.h"
#include "materials/surface_at.h"
#include "materials/texture.h"
#include "media/medium.h"
#include "media/phase.h"
#include "transport/medium_flight.h"

/* Dimension pairs of the sampler per path vertex: (branch choice, roulette), the light (triangle
 * and point), the direction, and (the lobe's azimuth, —) drawn only for a lobe; in a scene with
 * scattering media a fifth, (the flight's bin, its distance) for the flight that reaches the
 * vertex (medium_flight.h); pair 0 is the pixel position. */
#if KASHA_SCATTERING
#define KASHA_CAMERA_PAIRS_PER_VERTEX 5
#else
#define KASHA_CAMERA_PAIRS_PER_VERTEX 4
#endif

/* What a path carries from vertex to vertex. */
typedef struct {
  PathWeight p;
  float start;    /* pw_magnitude at the camera: what roulette and the depth guard compare with */
  float3 org, dir;
  float3 prev_x;  /* the previous vertex itself (org is offset off its surface) */
  float prev_pdf; /* the density with which the last bounce chose dir, for MIS with NEE */
  bool specular;  /* the camera ray, or a mirror bounce: emission is not also sampled by NEE */
  int depth;      /* the vertex the path is at */
  float eta_scale; /* the product of etap² over the refractions so far: roulette sees the weight
                    * without radiance's 1/etap² (pbrt-v4's etaScale), which a path undoes on leaving */
#if KASHA_DISPERSION
  int bin; /* the one bin the path carries after a dispersive interface, -1 before */
#endif
#if KASHA_MEDIA
  int medium; /* the medium the path travels in (media/medium.h), -1: vacuum */
#endif
} CameraWalk;

/* A vertex of the walk: the hit, its surface, the branch probabilities (gloss, passive,
 * fluorescent) and the vertex's sample values. */
typedef struct {
  HitPoint h;
  Surface surf;
  float3 probs;
  float2 u_choice, u_light, u_dir;
#if KASHA_SCATTERING
  bool in_medium; /* a scattering in the walk's medium at h.x (no surface: h's other fields unset) */
#endif
} CameraVertex;

inline void walk_start(CameraWalk* w, const SceneView* s, const FilmView* f, float3 org, float3 dir) {
  pw_init(&w->p, f);
  w->start = pw_magnitude(&w->p, f);
  w->org = org;
  w->dir = dir;
  w->prev_x = org;
  w->prev_pdf = 0.0f;
  w->specular = true;
  w->depth = 0;
  w->eta_scale = 1.0f;
#if KASHA_DISPERSION
  w->bin = -1;
#endif
#if KASHA_MEDIA
  w->medium = s->camera_medium;
#endif
}

#if KASHA_MEDIA
/* T ← T·diag(transmittance): the path's colour through the media of the trail. */
inline void pw_attenuate(PathWeight* p, const SceneView* s, const MediaTrail* t) {
  if (!trail_empty(t)) pw_transmit(p, s, t, 1.0f);
}

#endif

/* The walk's next surface (intersect_surface); in a scene with media, through interfaces, the
 * path's colour attenuated by the media on the way (media/medium.h). */
inline bool walk_intersect(CameraWalk* w, const SceneView* s, HitPoint* h) {
#if KASHA_MEDIA
  MediaTrail trail;
  trail_clear(&trail);
  bool hit = intersect_through(s, w->org, w->dir, &w->medium, &trail, h);
  pw_attenuate(&w->p, s, &trail);
  return hit;
#else
  return intersect_surface(s, w->org, w->dir, h);
#endif
}

#if KASHA_INFINITE_LIGHTS
/* A path that leaves the scene sees the infinite lights, each MIS-weighted against next-event
 * estimation's choice of that direction unless a specular bounce led there. */
inline void walk_escaped(const CameraWalk* w, const SceneView* s, const FilmView* f, float* rows) {
  for (int k = 0; k < s->light_sources; ++k) {
    const __global KLight* l = &s->lights[k];
    if (l->type != KASHA_LIGHT_INFINITE) continue;
    float weight = w->specular ? 1.0f : mis_weight(w->prev_pdf, infinite_light_pdf(s, l, w->dir));
    pw_add(&w->p, f, infinite_light_spectrum(s, l, w->dir), 0, weight, rows);
  }
}
#endif

#if KASHA_SCATTERING
/* A scattering vertex's samples (as a surface vertex's); false where --max-depth ends the path. */
inline bool walk_medium_samples(CameraWalk* w, Sampler* sampler, CameraVertex* v) {
#ifdef KASHA_DEPTH_CAP
  if (w->depth >= KASHA_DEPTH_CAP) return false;
#endif
  sampler_at(sampler, 1 + w->depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
  v->u_choice = sample_2d(sampler);
  v->u_light = sample_2d(sampler);
  v->u_dir = sample_2d(sampler);
  return true;
}
#endif

/* The path's next vertex: adds the emission it hits to rows (MIS-weighted against next-event
 * estimation unless a specular bounce led there), then loads the vertex's surface, branch
 * probabilities and samples into v. False where the path ends: it escaped, no branch carries
 * anything on, the --max-depth cap is reached, or the depth guard (walk_cut) stopped it. */
inline bool walk_vertex(CameraWalk* w, const SceneView* s, const FilmView* f, Sampler* sampler, CameraVertex* v,
                        float* rows) {
  if (w->depth == KASHA_MAX_PATH_DEPTH) return false;
  HitPoint* h = &v->h;
#if KASHA_SCATTERING
  sampler_at(sampler, 1 + w->depth * KASHA_CAMERA_PAIRS_PER_VERTEX + 4);
  float tbar;
  int reached = flight(&w->p, s, f, w->org, w->dir, &w->medium, sample_2d(sampler), h, &tbar);
  v->in_medium = reached == KASHA_FLIGHT_SCATTERED;
  if (v->in_medium) {
#if KASHA_MEDIUM_EMISSION
    /* The medium's emission at the collision, σa·Le over the flight's density (medium_flight.h);
     * no other technique finds it, so it counts whole (pbrt-v4's volpath does the same, and
     * only below its maxdepth: the collision would be one scattering vertex more). */
    bool emits = true;
#ifdef KASHA_DEPTH_CAP
    emits = w->depth < KASHA_DEPTH_CAP;
#endif
    if (emits) medium_emission_add(&w->p, s, f, w->medium, h->x, rows);
#endif
    return walk_medium_samples(w, sampler, v);
  }
  bool hit = reached == KASHA_FLIGHT_SURFACE;
#else
  bool hit = walk_intersect(w, s, h);
#endif
  if (!hit) {
#if KASHA_INFINITE_LIGHTS
    walk_escaped(w, s, f, rows);
#endif
    return false;
  }
  if (h->emitter >= 0 && h->front) {
    float weight = 1.0f;
    if (!w->specular) weight = mis_weight(w->prev_pdf, light_pdf_from(s, h->tri, w->prev_x, h->x, dot(h->n, -w->dir)));
#if KASHA_EMISSION_TEXTURES
    weight *= emission_factor(s, h->tri, h->b.x, h->b.y);
#endif
    pw_add(&w->p, f, emitter_spectrum(s, h->emitter), 0, weight, rows);
  }
#ifdef KASHA_DEPTH_CAP
  /* Emission here ends a path of `depth` scattering vertices; next-event estimation or a bounce
   * from here would make one more than the cap allows. */
  if (w->depth >= KASHA_DEPTH_CAP) return false;
#endif
#if KASHA_SHADING_NORMALS
  /* Seen from below the shading normal's hemisphere, the surface scatters nothing (hit_seen). */
  if (!hit_seen(h, w->dir)) return false;
#endif
  load_surface_at(s, h, &v->surf);
  v->probs = surface_specular(&v->surf) ? (float3)(1.0f, 0.0f, 0.0f) : branch_probabilities(&w->p, f, &v->surf);
  if (v->probs.x + v->probs.y + v->probs.z <= 0.0f) return false;
  sampler_at(sampler, 1 + w->depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
  v->u_choice = sample_2d(sampler);
  v->u_light = sample_2d(sampler);
  v->u_dir = sample_2d(sampler);
  return true;
}

/* The medium the walk arrived in (-1 without media), which next-event estimation leaves by. */
inline int walk_medium(const CameraWalk* w) {
#if KASHA_MEDIA
  return w->medium;
#else
  return -1;
#endif
}

/* Next-event estimation at the vertex where a Lambert part (`lambert`) or the gloss lobe takes
 * light, MIS against the branches `probs` that could also reach it (next_event.h). */
inline void walk_next_event(const CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                            bool lambert, float3 probs, float* rows) {
  const Surface* surf = &v->surf;
  if (s->light_count > 0 && (lambert || (surf->g > 0.0f && !surf->mirror)))
    next_event(&w->p, s, f, surf, &v->h, walk_medium(w), -w->dir, probs, v->u_light, rows);
}

/* The gloss branch, chosen with probability probs.x: white, weight g over that (times the lobe's
 * cosine ratio); the mirror direction, or one drawn from the lobe (a rough coat's: coat.h). False: the lobe's direction
 * lies below the horizon, absorbed. */
inline bool walk_gloss(CameraWalk* w, const SceneView* s, const CameraVertex* v, Sampler* sampler) {
  const Surface* surf = &v->surf;
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    /* A rough coat's GGX lobe: weight F G / G1 over the branch's probability. */
    Frame fr = frame_of(v->h.ns);
    float3 wi;
    float weight, pdf;
    if (!coat_lobe_sample(surf, to_local(&fr, -w->dir), v->u_dir, &wi, &weight, &pdf)) return false;
    w->dir = to_world(&fr, wi);
    w->specular = false;
    w->prev_pdf = v->probs.x * pdf;
    pw_scatter_diagonal(&w->p, 0, weight / v->probs.x);
    return true;
  }
#endif
  float3 ns = v->h.ns, mirror = reflect_dir(w->dir, ns);
  float weight = surf->g;
  if (surf->mirror) {
    w->dir = mirror;
    w->specular = true;
  } else {
    float pdf;
    float3 wi = sample_lobe(surf->m, s->lobes, mirror, v->u_dir.x, v->u_dir.y, sample_2d(sampler).x, &pdf);
    float ci = dot(wi, ns), co = dot(-w->dir, ns);
    if (ci <= 0.0f) return false;
    weight = weight * 2.0f * ci / (ci + co);
    w->dir = wi;
    w->specular = false;
    w->prev_pdf = v->probs.x * pdf;
  }
  pw_scatter_diagonal(&w->p, 0, weight / v->probs.x);
  return true;
}

#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
/* A specular interface (surface_specular): a smooth dielectric reflects with probability F and
 * refracts otherwise, so the weight is 1 either way but for radiance's 1/etap² on refraction
 * (radiance is compressed into the narrower cone of the denser side); a smooth conductor reflects
 * with weight F(lambda). Either way the next emission hit counts whole (a delta bounce). A
 * dispersive dielectric first narrows the path to one bin (pw_choose_bin, on the vertex's unused
 * direction sample) unless it already is one. False: the path carries nothing. */
inline bool walk_specular(CameraWalk* w, const FilmView* f, const CameraVertex* v) {
  const Surface* surf = &v->surf;
  float3 ns = v->h.ns;
  float cos_i = -dot(w->dir, ns);
  w->specular = true;
#if KASHA_DIELECTRIC
  if (surf->kind == KASHA_KIND_DIELECTRIC) {
    float eta = surf->eta;
#if KASHA_DISPERSION
    if (surf->dispersive) {
      if (w->bin < 0) w->bin = pw_choose_bin(&w->p, f, v->u_dir.x);
      if (w->bin < 0) return false;
      eta = surf->eta_bins[w->bin];
    }
#endif
#if KASHA_THIN
    if (surf->thin) {
      /* Reflects with R', else straight on: direction, weight and eta_scale unchanged. */
      if (v->u_choice.x < thin_dielectric_reflectance(cos_i, eta)) w->dir = reflect_dir(w->dir, ns);
      return true;
    }
#endif
    float etap = v->h.front ? eta : 1.0f / eta;
    if (v->u_choice.x < fresnel_dielectric(cos_i, etap)) {
      w->dir = reflect_dir(w->dir, ns);
    } else {
      w->dir = refract_dir(w->dir, ns, cos_i, etap);
      pw_scatter_diagonal(&w->p, 0, 1.0f / (etap * etap));
      w->eta_scale *= etap * etap;
    }
    return true;
  }
#endif
#if KASHA_CONDUCTOR
  pw_scatter_conductor(&w->p, surf->eta_c, surf->k_c, surf->coat_c, cos_i);
  w->dir = reflect_dir(w->dir, ns);
#endif
  return true;
}
#endif

#if KASHA_ROUGH
/* A dielectric's index for this path: at a dispersive one, the path's bin (chosen here, on u, if
 * the path has none yet). Negative: the path carries nothing. */
inline float walk_eta(CameraWalk* w, const FilmView* f, const Surface* surf, float u) {
#if KASHA_DISPERSION
  if (surf->dispersive) {
    if (w->bin < 0) w->bin = pw_choose_bin(&w->p, f, u);
    return w->bin < 0 ? -1.0f : surf->eta_bins[w->bin];
  }
#endif
  return surface_eta(surf);
}

/* Next-event estimation at a rough interface (rough_interface.h): one light point, on either side
 * of the surface (a rough dielectric transmits), weighed by MIS against sampling the interface. */
inline void walk_rough_next_event(const CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                  float eta, float* rows) {
  if (s->light_count == 0) return;
  const Surface* surf = &v->surf;
  float pdf_light;
  LightPoint lp = sample_light_from(s, v->h.x, v->u_light, &pdf_light);
  if (!(pdf_light > 0.0f)) return;
  float3 to = lp.position - v->h.x;
  float dist = length(to);
  if (!(dist > v->h.eps + lp.eps)) return;
  float3 wi = to / dist;
  float cos_l = -dot(lp.normal, wi);
  if (cos_l <= 0.0f) return;
  Frame fr = surface_frame(surf, hit_front(&v->h));
  float3 wo_l = to_local(&fr, -w->dir), wi_l = to_local(&fr, wi);
  float pdf, cos_m = 0.0f, fv;
  if (surf->kind == KASHA_KIND_DIELECTRIC)
    fv = rough_dielectric_eval(wo_l, wi_l, eta, surf->alpha, true, &pdf);
  else
    fv = conductor_lobe_eval(surf, wo_l, wi_l, &pdf, &cos_m);
  if (!(fv > 0.0f)) return;
#if KASHA_SHADING_NORMALS
  /* Offset by the geometric side the light lies on, and no light through the wrong one. */
  float3 toward = dot(wi, v->h.n) > 0.0f ? v->h.n : -v->h.n;
  if ((wi_l.z > 0.0f) != (dot(wi, v->h.n) > 0.0f)) return;
#else
  float3 toward = wi_l.z > 0.0f ? v->h.n : -v->h.n;
#endif
  const __global float* le = light_point_spectrum(s, &lp);
#if KASHA_MEDIA
  le = segment_light(s, v->h.x, toward, v->h.eps, wi, dist, lp.eps / cos_l,
                     medium_after(s, v->h.tri, v->h.n, wi, w->medium), le);
  if (!le) return;
#else
  if (segment_occluded(s, v->h.x, toward, v->h.eps, wi, dist, lp.eps / cos_l)) return;
#endif
#if KASHA_LIGHT_SOURCES
  float scale = fv * fabs(wi_l.z) / pdf_light * lp.scale * mis_weight(pdf_light, lp.delta ? 0.0f : pdf);
#elif KASHA_EMISSION_TEXTURES
  float scale = fv * fabs(wi_l.z) / pdf_light * lp.scale * mis_weight(pdf_light, pdf);
#else
  float scale = fv * fabs(wi_l.z) / pdf_light * mis_weight(pdf_light, pdf);
#endif
#if KASHA_CONDUCTOR
  if (surf->kind == KASHA_KIND_CONDUCTOR) {
    pw_add_conductor(&w->p, f, le, surf->eta_c, surf->k_c, surf->coat_c, cos_m, scale, rows);
    return;
  }
#endif
  pw_add(&w->p, f, le, 0, scale, rows);
}

/* A direction drawn from a rough interface's visible normals at index eta (a reflection or, for
 * a dielectric, a refraction, chosen by the facet's Fresnel reflectance; a conductor's F(λ)
 * applied bin by bin). False: the path ends. */
inline bool walk_rough_scatter(CameraWalk* w, const CameraVertex* v, float eta) {
  const Surface* surf = &v->surf;
  Frame fr = surface_frame(surf, hit_front(&v->h));
  float3 wo = to_local(&fr, -w->dir);
  InterfaceSample smp;
  bool ok = surf->kind == KASHA_KIND_DIELECTRIC
                ? rough_dielectric_sample(wo, eta, surf->alpha, true, v->u_choice.x, v->u_dir, &smp)
                : conductor_lobe_sample(surf, wo, v->u_dir, &smp);
  if (!ok || !(smp.pdf > 0.0f)) return false;
#if KASHA_CONDUCTOR
  if (surf->kind == KASHA_KIND_CONDUCTOR) pw_scatter_conductor(&w->p, surf->eta_c, surf->k_c, surf->coat_c, smp.cos_m);
#endif
  pw_scatter_diagonal(&w->p, 0, smp.weight);
  if (smp.transmitted) {
    float etap = wo.z > 0.0f ? eta : 1.0f / eta;
    w->eta_scale *= etap * etap;
  }
  w->dir = to_world(&fr, smp.wi);
  w->specular = false;
  w->prev_pdf = smp.pdf;
  return true;
}

/* A rough interface: next-event estimation, then a direction (walk_rough_scatter). The fourth
 * sample pair of the vertex picks a dispersive dielectric's bin. False: the path ends. */
inline bool walk_rough(CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v, Sampler* sampler,
                       float* rows) {
  const Surface* surf = &v->surf;
  float eta = surf->kind == KASHA_KIND_DIELECTRIC ? walk_eta(w, f, surf, sample_2d(sampler).x) : 1.0f;
  if (eta < 0.0f) return false;
  walk_rough_next_event(w, s, f, v, eta, rows);
  return walk_rough_scatter(w, v, eta);
}
#endif

/* A Lambert branch chosen with probability `prob`: a cosine-distributed direction. */
inline void lambert_bounce(CameraWalk* w, const CameraVertex* v, float prob) {
  float3 ns = v->h.ns;
  w->dir = sample_cosine_hemisphere(ns, v->u_dir.x, v->u_dir.y);
  w->specular = false;
  w->prev_pdf = prob * cosine_hemisphere_pdf(dot(w->dir, ns));
}

/* The Lambert bounce's factor beyond ρ/π: a coat's t(θo) t(θi) / η² (coat.h), else 1. */
inline float lambert_weight(const CameraWalk* w, const CameraVertex* v) {
#if KASHA_COATED
  return surface_lambert_weight(&v->surf, dot(w->dir, v->h.ns));
#else
  return 1.0f;
#endif
}

/* The passive branch chosen with probability `prob`: a cosine-distributed direction on the side the
 * path arrived from (weight ρ), or through a transmitting surface (τ), the side drawn on the
 * direction sample with the material's share (surface_side_share). */
inline void passive_bounce(CameraWalk* w, const CameraVertex* v, float prob) {
#if KASHA_TRANSMISSION
  float st = v->surf.share_t;
  if (st > 0.0f) {
    bool through = v->u_dir.x < st;
    float u = through ? v->u_dir.x / st : (v->u_dir.x - st) / (1.0f - st);
    float side = through ? st : 1.0f - st;
    float3 n = through ? -v->h.ns : v->h.ns;
    w->dir = sample_cosine_hemisphere(n, min(u, 0x1.fffffep-1f), v->u_dir.y);
    w->specular = false;
    w->prev_pdf = prob * side * cosine_hemisphere_pdf(dot(w->dir, n));
    pw_scatter_diagonal(&w->p, surface_side_spectrum(&v->surf, through), 1.0f / (prob * side));
    return;
  }
#endif
  lambert_bounce(w, v, prob);
  pw_scatter_diagonal(&w->p, v->surf.rho, lambert_weight(w, v) / prob);
}

/* After the vertex's bounce: the end of a path that would leak through the surface (hit_no_leak),
 * Russian roulette from the path's KASHA_CAMERA_ROULETTE_FROM-th vertex
 * on (false: the path ends), then the next ray's origin just off the surface. */
/* Russian roulette from the path's KASHA_CAMERA_ROULETTE_FROM-th vertex on, on u; false: the
 * path ends. */
inline bool walk_roulette(CameraWalk* w, const FilmView* f, float u) {
  if (w->depth >= KASHA_CAMERA_ROULETTE_FROM) {
    float keep = roulette(pw_magnitude(&w->p, f) * w->eta_scale / w->start, u);
    if (keep == 0.0f) return false;
    if (keep != 1.0f) pw_scatter_diagonal(&w->p, 0, keep);
  }
  return true;
}

inline bool walk_on(CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v) {
  if (!hit_no_leak(&v->h, w->dir)) return false;
  if (!walk_roulette(w, f, v->u_choice.y)) return false;
  w->prev_x = v->h.x;
  /* Off the side the new direction leaves by: the far side after a refraction. */
  float3 ng = hit_ng(&v->h);
  float side = dot(w->dir, ng) >= 0.0f ? v->h.eps : -v->h.eps;
  w->org = v->h.x + ng * side;
#if KASHA_MEDIA
  w->medium = medium_after(s, v->h.tri, v->h.n, w->dir, w->medium);
#endif
  ++w->depth;
  return true;
}

#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
/* A vertex on glass or metal (surface_specular), the same in backward and photon mapping's camera
 * pass: a rough interface (next-event estimation and a sampled direction) or a smooth one (a delta
 * bounce), then on. False: the path ends. */
inline bool walk_interface(CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                           Sampler* sampler, float* rows) {
#if KASHA_ROUGH
  if (surface_rough(&v->surf)) return walk_rough(w, s, f, v, sampler, rows) && walk_on(w, s, f, v);
#endif
  return walk_specular(w, f, v) && walk_on(w, s, f, v);
}
#endif

#if KASHA_SCATTERING
/* A collision's branches in medium m, as a surface's (branch_probabilities): elastic scattering
 * (σs) and each fluorophore's re-emission (its yield, its ê as the path sees it, Σ of its
 * absorption), in proportion to the energy each brings to the film under equal-energy light;
 * probs[0] elastic, probs[1 + k] fluorophore k. False: no branch carries anything on. */
inline bool medium_branches(const CameraWalk* w, const SceneView* s, const FilmView* f, const __global KMedium* m,
                            float* probs) {
  float sum = probs[0] = pw_energy(&w->p, f, medium_scattering(s, m));
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) {
    const __global KFluorophore* fl = &m->fluorophore[k];
    probs[1 + k] = fl->yield * fl->absorption_sum * pw_energy(&w->p, f, s->spectra + fl->emission);
    sum += probs[1 + k];
  }
#endif
  if (!(sum > 0.0f)) return false;
  probs[0] /= sum;
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) probs[1 + k] /= sum;
#endif
  return true;
}

/* A light point for next-event estimation from x in a medium (no surface, no offset), drawn on u:
 * its density *pdf_light, the direction *wi and distance *dist to it and the cosine *cos_l there.
 * False: none usable. */
inline bool collision_light_point(const SceneView* s, float3 x, float2 u, LightPoint* lp, float* pdf_light, float3* wi,
                                  float* dist, float* cos_l) {
  *lp = sample_light_from(s, x, u, pdf_light);
  if (!(*pdf_light > 0.0f)) return false;
  float3 to = lp->position - x;
  *dist = length(to);
  if (!(*dist > lp->eps)) return false;
  *wi = to / *dist;
  *cos_l = -dot(lp->normal, *wi);
  return *cos_l > 0.0f;
}

/* Next-event estimation from a collision: one light point, its light through the media on the way
 * (segment_light), sent on by each branch — σs and the phase function, each fluorophore's
 * absorption, yield and ê, isotropically — each weighed by MIS against its own branch's sampling
 * of that direction. */
inline void walk_medium_next_event(const CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                   const __global KMedium* m, const float* probs, float* rows) {
  if (s->light_count == 0) return;
  float3 x = v->h.x, wi;
  float pdf_light, dist, cos_l;
  LightPoint lp;
  if (!collision_light_point(s, x, v->u_light, &lp, &pdf_light, &wi, &dist, &cos_l)) return;
  const __global float* le = segment_light(s, x, (float3)(0.0f, 0.0f, 0.0f), 0.0f, wi, dist, lp.eps / cos_l, w->medium,
                                           light_point_spectrum(s, &lp));
  if (!le) return;
  float base = 1.0f / pdf_light;
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  base *= lp.scale;
#endif
#if KASHA_LIGHT_SOURCES
  float reach = lp.delta ? 0.0f : 1.0f; /* a delta light no direction sampling finds */
#else
  const float reach = 1.0f;
#endif
  float phase = hg_phase(dot(-w->dir, wi), m->g);
  pw_add(&w->p, f, medium_scattering(s, m), le,
         base * phase * mis_weight(pdf_light, reach * probs[0] * phase), rows);
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) {
    const __global KFluorophore* fl = &m->fluorophore[k];
    float absorbed = fl->yield * spectrum_dot(KASHA_BINS, 0, s->spectra + fl->absorption, le) * KASHA_INV_4PI;
    pw_add(&w->p, f, s->spectra + fl->emission, 0,
           base * absorbed * mis_weight(pdf_light, reach * probs[1 + k] * KASHA_INV_4PI), rows);
  }
#endif
}

/* A collision's bounce in medium m, its branches' probabilities `probs` (medium_branches): one
 * branch on u_choice.x — elastic scattering, σs and a direction from the Henyey–Greenstein phase
 * function (whose weight is 1), or a fluorophore's re-emission, rank-1 through its ê and
 * absorption (path_weight.h) and isotropic — over its probability, and roulette. The path goes on
 * from the point itself: no surface to step off. False: the path ends. */
inline bool walk_medium_scatter(CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                const __global KMedium* m, const float* probs) {
  float pdf;
  int branch = medium_branch(probs, m->fluorophores, v->u_choice.x);
  if (!(probs[branch] > 0.0f)) return false;
  if (branch == 0) {
    w->dir = hg_sample(-w->dir, m->g, v->u_dir, &pdf);
    pw_scatter_diagonal(&w->p, medium_scattering(s, m), 1.0f / probs[0]);
    w->prev_pdf = probs[0] * pdf;
  }
#if KASHA_FLUORESCENCE
  else {
    const __global KFluorophore* fl = &m->fluorophore[branch - 1];
    w->dir = sample_uniform_sphere(v->u_dir);
    pw_scatter_fluorescent(&w->p, f, s->spectra + fl->emission, s->spectra + fl->absorption,
                           fl->yield / probs[branch]);
    w->prev_pdf = probs[branch] * KASHA_INV_4PI;
#if KASHA_DISPERSION
    w->bin = -1; /* re-emission spreads the path over the absorption spectrum again */
#endif
  }
#endif
  w->specular = false;
  if (!walk_roulette(w, f, v->u_choice.y)) return false;
  w->prev_x = v->h.x;
  w->org = v->h.x;
  ++w->depth;
  return true;
}

/* A collision in the walk's medium (walk_vertex's in_medium): next-event estimation, then the
 * bounce (walk_medium_scatter). False: the path ends. */
inline bool walk_medium_vertex(CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                               float* rows) {
  const __global KMedium* m = &s->media[w->medium];
  float probs[1 + KASHA_MEDIUM_FLUOROPHORES];
  if (!medium_branches(w, s, f, m, probs)) return false;
  walk_medium_next_event(w, s, f, v, m, probs, rows);
  return walk_medium_scatter(w, s, f, v, m, probs);
}
#endif

/* What the path still carried (relative to its start) if the depth guard cut it, else 0. */
inline float walk_cut(const CameraWalk* w, const FilmView* f) {
  return w->depth == KASHA_MAX_PATH_DEPTH ? pw_magnitude(&w->p, f) / w->start : 0.0f;
}

#endif
