/* Vertex connection and merging (docs/integrators.md#vertex-connection-and-merging): Georgiev,
 * Křivánek, Davidovič and Slusallek 2012, as SmallVCM's vertexcm.hxx lays it out, with kasha's
 * transport — light subpaths are spectral photons (photon_transport.h: fluorescent re-emission,
 * constant-energy branching), camera subpaths carry a diagonal or rank-1 colour (path_weight.h),
 * so a connection T·f·G·f·Φ and a merge T·f·Φ cost O(N) and never pair wavelengths.
 *
 * An iteration is two launches and a grid:
 * 1. vcm_light_pass: light subpaths (one per pixel, 32 in a caustic-lit view; ppm at least
 *    2^16); each vertex with a non-delta part is stored (vcm_layout.h), linked to its path's
 *    previous one, and (connecting modes) splatted to the camera, MIS-weighted;
 * 2. the hashed grid over the stored vertices (hash_grid.cl; merging modes), cells of 2r;
 * 3. vcm_camera_pass: one camera path per pixel; at each vertex with a non-delta part, emission
 *    hit, next-event estimation, connections to its light subpath's vertices (connecting modes)
 *    and merges with the stored vertices within r (merging modes), each MIS-weighted; where the
 *    light seen through delta bounces alone has an edge, that light from extra samples
 *    (vcm_seen_light).
 * Modes are build options: KASHA_VCM_CONNECT and KASHA_VCM_MERGE both (vcm), connections only
 * (bpt), merges only (ppm: unweighted, once at the camera path's first non-delta vertex).
 *
 * MIS is the balance heuristic through Georgiev's recursive partial weights dVCM, dVC, dVM, each
 * subpath's kept from its start (SmallVCM's names). Kasha chooses branches by the path's
 * spectrum, which the other subpath cannot know; the weights use pseudo-densities both sides
 * evaluate alike from the geometry and the material alone (vcm_pdf: the gloss share from the
 * material, a light point by area), so every path's weights still sum to one, while each
 * contribution divides by the density it was truly sampled with — unbiased for connections, as
 * consistent as photon mapping for merges. */
#define KASHA_RECORD_FLOATS KASHA_VCM_FLOATS(KASHA_BINS)

#include "vcm_layout.h"

/* The grid holds only the vertices merges may use. */
#define KASHA_RECORD_IN_GRID(r) ((r)[KASHA_VCM_MERGEABLE(KASHA_BINS)] > 0.5f)

#include "camera.h"
#include "camera_splat.h"
#include "camera_walk.h"
#include "disc_coverage.h"
#include "hash_grid.cl"
#include "photon_transport.h"

#ifndef KASHA_VCM_CONNECT
#define KASHA_VCM_CONNECT 1
#endif
#ifndef KASHA_VCM_MERGE
#define KASHA_VCM_MERGE 1
#endif
/* Where vcm merges (--merges): at every camera vertex that is not delta (1, Georgiev et al.), or
 * only at the first (0, as SPPM gathers; the default, with caustic merges below): then no light
 * vertex but one the camera sees directly is a merging vertex of any full path — the light subpaths' partial weights leave
 * their own merges out, light tracing keeps the merge at the vertex it splats, and a connection
 * counts no merge on the light side — so every path still has its weights summing to one, and a
 * camera path makes one range query instead of one a bounce. */
#ifndef KASHA_VCM_MERGE_EVERY
#define KASHA_VCM_MERGE_EVERY 0
#endif
/* --merges caustic (the default but in caustic-lit views, host/integrators/vcm/vcm_integrator.cpp;
 * with merges at the first vertex): a merge counts only for a path
 * whose light arrived at the merging vertex from a delta bounce (a mirror, glass: a caustic), the
 * paths no connection and no next-event estimation reaches. Elsewhere connections do better than
 * a count of photons in a disc, and a merge there costs a range query for almost no weight; so
 * the grid holds only the light vertices reached from a delta bounce (none on a diffuse scene).
 * Every technique knows whether the path it makes is such: a light subpath from its last bounce;
 * a camera path from the bounce after its merging vertex (the part of dVC that merge put in is
 * kept apart until then, VcmCamera), so every path's weights still sum to one. */
#ifndef KASHA_VCM_MERGE_CAUSTIC
#define KASHA_VCM_MERGE_CAUSTIC 0
#endif

#define VCM_FLOATS KASHA_VCM_FLOATS(KASHA_BINS)
/* Floats of a work item's spectra: a light vertex's f·Φ, then room for the light vertex's
 * surface (textured, coated) apart from the camera vertex's in the scene's scratch. */
#define VCM_SPECTRA (KASHA_BINS + KASHA_SCRATCH_FLOATS)

/* Test hooks (tests/vcm_test.cpp): KASHA_VCM_LENGTH > 0 keeps only the contributions of paths of
 * that many segments; KASHA_VCM_EMISSION_ONLY keeps only camera paths hitting emitters,
 * unweighted (path tracing without next-event estimation: the plain estimate the weighted
 * techniques must add up to); KASHA_VCM_DROP_DENSITY leaves next-event estimation's density out
 * of light tracing's weight, a wrong weight the tests must catch. */
#ifndef KASHA_VCM_LENGTH
#define KASHA_VCM_LENGTH 0
#endif
#ifndef KASHA_VCM_EMISSION_ONLY
#define KASHA_VCM_EMISSION_ONLY 0
#endif
#ifndef KASHA_VCM_DROP_DENSITY
#define KASHA_VCM_DROP_DENSITY 0
#endif
#define VCM_LENGTH_COUNTS(segments) (KASHA_VCM_LENGTH == 0 || (segments) == KASHA_VCM_LENGTH)

/* The MIS factors of an iteration with merging radius r and L light subpaths, η = κ π r² L / spp
 * (SmallVCM's mMisVmWeightFactor and mMisVcWeightFactor): a merge weighs η against a
 * connection's 1, a connection 1/η against a merge; 0 for a technique the mode leaves out. */
inline float vcm_merge_factor(float eta) { return KASHA_VCM_MERGE ? eta : 0.0f; }
inline float vcm_connect_factor(float eta) { return KASHA_VCM_CONNECT ? 1.0f / eta : 0.0f; }

/* Light tracing's share ν: the weights count light tracing as ν·L samples of a pixel against its
 * spp camera paths (SmallVCM counts L). The balance heuristic assumes independent samples, but a
 * pixel's camera paths are Owen-scrambled Sobol points — stratified over the pixel, the first
 * bounces and next-event estimation's light points — while the splats that land in a pixel are
 * not, so at equal count the camera side is far less noisy (backward's RMSE on the torus after
 * 20 s: 3.55 with Sobol, 8.72 with independent samples). ν = 1/10 with Sobol, 1 with
 * --sampler independent, where the heuristic's assumption holds (docs/integrators.md). Light
 * tracing keeps the whole weight where no camera technique reaches a path; both subpaths use the
 * same ν, so every path's weights still sum to one. */
#if KASHA_SOBOL
#define KASHA_VCM_TRACING_SHARE 0.1f
#else
#define KASHA_VCM_TRACING_SHARE 1.0f
#endif

/* An iteration's merging radius: one for every vertex (per_unit 0: --radius, --merges every), or
 * (per_unit > 0) a pixel's footprint where the camera path merges — per_unit times the distance it
 * travelled there, through delta bounces — up to `radius`. Either subpath finds the radius of a
 * vertex where the camera path would merge (light tracing: its distance to the camera), so both
 * weigh merges alike. η = eta_unit · r² with eta_unit = κ π L over the pixel's camera paths (the host's
 * kMergeWeight κ weighs merges down where connections also reach a path). */
typedef struct {
  float eta_unit, radius, per_unit;
} VcmRadius;

inline float vcm_radius_at(const VcmRadius* r, float travelled) {
  return r->per_unit > 0.0f ? fmin(r->per_unit * travelled, r->radius) : r->radius;
}
inline float vcm_eta_at(const VcmRadius* r, float radius) { return r->eta_unit * radius * radius; }

/* A vertex connects where its surface has a non-delta part: a Lambert part (bare or under a
 * coat), a tabulated gloss lobe, a rough coat's lobe, or a rough dielectric or conductor. It
 * merges where it has a Lambert part or a tabulated lobe: a rough interface only connects, a
 * choice both subpaths make alike from the material (the recursion leaves its merge out); ppm
 * merges at a rough conductor too. */
inline bool vcm_connectible(const Surface* surf) {
  if (surface_rough(surf)) return true;
  if (surface_specular(surf)) return false;
  return surface_has_lambert(surf) || (surf->g > 0.0f && !surf->mirror);
}
inline bool vcm_mergeable(const Surface* surf) {
#if KASHA_CONDUCTOR
  /* ppm, merges alone, must merge at a rough conductor: else a delta light's reflection in it
   * (a sun, a spot) would reach the camera by no technique. */
  if (!KASHA_VCM_CONNECT && surface_rough(surf) && surf->kind == KASHA_KIND_CONDUCTOR) return true;
#endif
  if (surface_specular(surf)) return false;
  return surface_has_lambert(surf) || (surf->g > 0.0f && !surf->mirror);
}

/* The Lambert parts' mean reflectance and excitation (after textures and a coat's series), from
 * the material alone: what the pseudo-density mixes the gloss part against. */
inline float vcm_lambert_mean(const Surface* surf) {
  float lambert = 0.0f;
  if (surf->passive)
    for (int i = 0; i < KASHA_BINS; ++i) lambert += surf->rho[i];
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) lambert += surf->a_sum;
#endif
  return lambert / KASHA_BINS;
}

/* The gloss part's share of the pseudo-density for a subpath that met the vertex at |cos| mu:
 * g against the Lambert parts' mean, for a coat both taken at mu (its Fresnel reflectance or
 * rough lobe albedo, and t(mu) for the parts under it); a function of the material and mu alone,
 * so both subpaths find the same density for the same pair of directions. */
inline float vcm_share(const Surface* surf, float lambert, float mu) {
#if KASHA_COATED
  if (surf->coated) {
    float g = coat_rough(surf) ? coat_table_at(surf, 0, mu) : fresnel_dielectric(mu, surf->m->coat_eta);
    float l = lambert * coat_transmission(surf, mu) * surf->m->coat_albedo;
    return g + l > 0.0f ? g / (g + l) : 0.0f;
  }
#endif
  if (!(surf->g > 0.0f)) return 0.0f;
  return surf->g / (surf->g + lambert);
}

/* The pseudo-density (per solid angle) of leaving the vertex along `to` having arrived from
 * `from` (both pointing away from the surface; ns the normal on from's side, nf the front one):
 * a rough interface's own density (at the material's index); else the Lambert parts' cosine and
 * the tabulated or coat lobe, mixed by the gloss share. A delta part is not in it. */
inline float vcm_pdf(const SceneView* s, const Surface* surf, float lambert, float3 ns, float3 nf, float3 from,
                     float3 to) {
#if KASHA_ROUGH
  if (surface_rough(surf)) {
    Frame fr = frame_of(nf);
    float pdf, cos_m;
    float3 wo = to_local(&fr, from), wi = to_local(&fr, to);
#if KASHA_DIELECTRIC
    if (surf->kind == KASHA_KIND_DIELECTRIC) {
      rough_dielectric_eval(wo, wi, surf->eta, surf->alpha, true, &pdf);
      return pdf;
    }
#endif
    rough_conductor_eval(wo, wi, surf->alpha, &pdf, &cos_m);
    return pdf;
  }
#endif
  float c = dot(ns, to);
  if (c <= 0.0f) return 0.0f;
  float share = vcm_share(surf, lambert, dot(ns, from));
  float pdf = (1.0f - share) * c * KASHA_INV_PI;
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    Frame fr = frame_of(ns);
    float lobe;
    coat_lobe_eval(surf, to_local(&fr, from), to_local(&fr, to), &lobe);
    return pdf + share * lobe;
  }
#endif
#if KASHA_GLOSS
  if (share > 0.0f && !surf->mirror) pdf += share * lobe_pdf(surf->m, s->lobes, dot(to, reflect_dir(-from, ns)));
#endif
  return pdf;
}

/* f(wo, wi) of a vertex's non-delta parts for radiance going from wi to wo (both away from the
 * surface; ns on the side it was met from, nf the front), split by how each part colours: the
 * Lambert parts' factor (1/π, times a coat's t t / η² with `other` the direction it was not met
 * from), a white part (tabulated or coat lobe, rough dielectric) and a rough conductor's f before
 * its F(λ) at cos_m. */
typedef struct {
  float lambert, white, conductor, cos_m;
#if KASHA_DISPERSION
  bool per_bin; /* a rough dispersive dielectric met by a spectrum: f bin by bin at o, i */
  float3 o, i;
#endif
} VcmF;

inline bool vcm_f_nonzero(const VcmF* fv) {
#if KASHA_DISPERSION
  if (fv->per_bin) return true;
#endif
  return fv->lambert > 0.0f || fv->white > 0.0f || fv->conductor > 0.0f;
}

/* eta: a rough dielectric's index for this path (a dispersive one's at the path's bin), or
 * negative for a spectrum not narrowed to a bin: evaluated bin by bin then (per_bin). */
inline VcmF vcm_eval(const SceneView* s, const Surface* surf, float3 ns, float3 nf, float3 wo, float3 wi, float3 other,
                     float eta) {
  VcmF r;
  r.lambert = r.white = r.conductor = r.cos_m = 0.0f;
#if KASHA_DISPERSION
  r.per_bin = false;
#endif
#if KASHA_ROUGH
  if (surface_rough(surf)) {
    Frame fr = frame_of(nf);
    float pdf;
    float3 o = to_local(&fr, wo), i = to_local(&fr, wi);
#if KASHA_CONDUCTOR
    if (surf->kind == KASHA_KIND_CONDUCTOR) {
      r.conductor = rough_conductor_eval(o, i, surf->alpha, &pdf, &r.cos_m);
      return r;
    }
#endif
#if KASHA_DISPERSION
    if (eta < 0.0f) {
      r.per_bin = true;
      r.o = o;
      r.i = i;
      return r;
    }
#endif
#if KASHA_DIELECTRIC
    r.white = rough_dielectric_eval(o, i, eta, surf->alpha, true, &pdf);
#endif
    return r;
  }
#endif
  if (!(dot(ns, wo) > 0.0f && dot(ns, wi) > 0.0f)) return r;
  r.lambert = KASHA_INV_PI * surface_lambert_weight(surf, dot(ns, other));
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    Frame fr = frame_of(ns);
    float pdf;
    r.white = coat_lobe_eval(surf, to_local(&fr, wo), to_local(&fr, wi), &pdf);
    return r;
  }
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) r.white = surf->g * lobe_brdf(surf->m, s->lobes, wo, wi, ns);
#endif
  return r;
}

/* The index a light vertex's rough dielectric is evaluated at: bin by bin (-1) where it disperses,
 * else its own. */
inline float vcm_light_eta(const Surface* surf) {
#if KASHA_DISPERSION
  if (surf->dispersive) return -1.0f;
#endif
#if KASHA_DIELECTRIC
  return surf->eta;
#else
  return 1.0f;
#endif
}

/* out = f·phi at a light vertex (vcm_eval's parts applied to the light's spectrum: ρ∘Φ, the
 * re-emission ê (a·Φ), white, a conductor's F(λ)). */
inline void vcm_light_apply(const Surface* surf, VcmF fv, const __global float* phi, __global float* out) {
#if KASHA_DISPERSION
  if (fv.per_bin) {
    float pdf;
    for (int i = 0; i < KASHA_BINS; ++i)
      out[i] = phi[i] == 0.0f ? 0.0f : phi[i] * rough_dielectric_eval(fv.o, fv.i, surf->eta_bins[i], surf->alpha, true, &pdf);
    return;
  }
#endif
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f) {
    for (int i = 0; i < KASHA_BINS; ++i)
      out[i] = phi[i] * fv.conductor * fresnel_conductor(fv.cos_m, surf->eta_c[i], surf->k_c[i]);
    return;
  }
#endif
  float l = surf->passive ? fv.lambert : 0.0f;
#if KASHA_FLUORESCENCE
  float fl = surf->fluorescent ? fv.lambert * spectrum_dot(KASHA_BINS, 0, surf->a, phi) : 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * l + fv.white) + surf->ehat[i] * fl;
#else
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * l + fv.white);
#endif
}

/* rows += scale · T·f·spectrum at a camera vertex (vcm_eval's parts, next_event.h's terms). */
inline void vcm_camera_apply(const PathWeight* p, const FilmView* f, const Surface* surf, VcmF fv,
                             const __global float* spectrum, float scale, float* rows) {
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f) {
    pw_add_conductor(p, f, spectrum, surf->eta_c, surf->k_c, fv.cos_m, scale * fv.conductor, rows);
    return;
  }
#endif
  if (fv.lambert > 0.0f) {
    if (surf->passive) pw_add(p, f, surf->rho, spectrum, scale * fv.lambert, rows);
#if KASHA_FLUORESCENCE
    if (surf->fluorescent)
      pw_add(p, f, surf->ehat, 0, scale * fv.lambert * spectrum_dot(KASHA_BINS, 0, surf->a, spectrum), rows);
#endif
  }
  if (fv.white > 0.0f) pw_add(p, f, spectrum, 0, scale * fv.white, rows);
}

/* A subpath's partial MIS weights after its vertex scattered it from `from` to `to` (SmallVCM's
 * SampleScattering): a delta bounce keeps them but for the cosine; any other divides by the
 * pseudo-density of the direction and carries the reverse one, with the vertex's own connection
 * and (where it merges) merge, whose part of dVC also goes to dvc_merge. Densities are about the
 * shading normal ns (nf: the front one), their turns to area about the geometric ng. False: no
 * density, the path ends. */
inline bool vcm_scattered(const SceneView* s, const Surface* surf, float lambert, float3 ns, float3 nf, float3 ng,
                          float3 from, float3 to, bool delta, bool merges, float vm, float vc, float* dvcm, float* dvc,
                          float* dvm, float* dvc_merge) {
  float cos_out = fabs(dot(ng, to)); /* turns the reverse density to area: the geometric cosine */
  if (delta) {
    *dvcm = 0.0f;
    *dvc *= cos_out;
    *dvm *= cos_out;
    *dvc_merge *= cos_out;
    return true;
  }
  float pdf = vcm_pdf(s, surf, lambert, ns, nf, from, to), rev = vcm_pdf(s, surf, lambert, ns, nf, to, from);
  if (!(pdf > 0.0f)) return false;
  /* dVC's part from the merge here, carried as dVC carries it (the camera's caustic merges). */
  *dvc_merge = cos_out / pdf * (*dvc_merge * rev + (merges ? vm : 0.0f));
  *dvc = cos_out / pdf * (*dvc * rev + *dvcm + (merges ? vm : 0.0f));
  *dvm = cos_out / pdf * (*dvm * rev + *dvcm * vc + (merges ? 1.0f : 0.0f));
  *dvcm = 1.0f / pdf;
  return true;
}

/* The side of a surface (normal n) a direction leaves by: where a shadow ray starts off. */
inline float3 vcm_toward(float3 n, float3 d) { return dot(n, d) >= 0.0f ? n : -n; }

/* hit_no_leak for a stored light vertex, which keeps its normals rather than its hit. */
inline bool vcm_no_leak(float3 ns, float3 ng, float3 d) {
#if KASHA_SHADING_NORMALS
  return (dot(d, ns) > 0.0f) == (dot(d, ng) > 0.0f);
#else
  return true;
#endif
}

/* Next-event estimation's density, per area of the light, of the point y on emitting triangle
 * `tri` (cos_light there) from x: what sample_light_from at x truly samples — by solid angle
 * where the triangle subtends enough, else by area. A function of x and y alone, so next-event
 * estimation, a camera path hitting the lamp and a light subpath's first vertex weigh it alike,
 * and a lamp near a surface is left to the technique that samples it well, as backward's MIS does
 * (an area density there would move the weight to the camera path's hits). */
inline float vcm_direct_area(const SceneView* s, int tri, float3 x, float3 y, float cos_light) {
  float3 d = y - x;
  return light_pdf_from(s, tri, x, y, cos_light) * cos_light / dot(d, d);
}

/* Arriving at a hit at distance t, cosine cos_in: the weights turn from solid angle to area (dVC's
 * part from a merge with it). */
inline void vcm_arrived(float t, float cos_in, float* dvcm, float* dvc, float* dvm, float* dvc_merge) {
  *dvcm *= t * t / cos_in;
  *dvc /= cos_in;
  *dvm /= cos_in;
  *dvc_merge /= cos_in;
}

#if KASHA_LIGHT_SOURCES
/* A light that is not a shape, for light travelling along d from it (SmallVCM's Emit and
 * Illuminate, the pick probability left to the caller): the density of the emission technique —
 * a photon's direction (point: 1/4π, spot: uniform in its cone), or its start on the disk as wide
 * as the scene facing the direction (distant: 1/πr²; infinite: the direction's density over
 * πr²) — and, as *direct, next-event estimation's density of the same light: 1 for a delta light
 * (a point or spot's 1/d² is the caller's), the direction's density for an infinite one. */
inline float vcm_source_emission(const SceneView* s, const __global KLight* l, float3 d, float* direct) {
  *direct = 1.0f;
  if (l->type == KASHA_LIGHT_POINT) return 0.25f * KASHA_INV_PI;
#if KASHA_SPOT_LIGHTS
  if (l->type == KASHA_LIGHT_SPOT) return 1.0f / (2.0f * KASHA_PI * (1.0f - l->cos_total));
#endif
  float disk = 1.0f / (KASHA_PI * l->radius * l->radius);
#if KASHA_INFINITE_LIGHTS
  if (l->type == KASHA_LIGHT_INFINITE) {
    *direct = infinite_light_pdf(s, l, -d) / l->pick;
    return *direct * disk;
  }
#endif
  return disk;
}

/* A point or spot light: at a finite place (its photons' first hit turns to area with t²). */
inline bool vcm_source_finite(const __global KLight* l) {
  return l->type == KASHA_LIGHT_POINT || l->type == KASHA_LIGHT_SPOT;
}
#endif

#if KASHA_VCM_CONNECT
/* A light vertex seen by the camera (light tracing, SmallVCM's ConnectToCamera): f Φ k / Δλ with
 * k = cos · importance (camera_connection), which is also the camera's density of the vertex per
 * area, weighed against every technique that samples it from the camera side — `spp` camera paths
 * a pixel against `paths` light subpaths. */
inline void vcm_splat(const SceneView* s, const FilmView* f, SplatTarget* t, const Surface* surf, float lambert,
                      bool merges, const HitPoint* h, float3 from, const Photon* p, float dvcm, float dvc,
                      const VcmRadius* radius, float paths, int spp) {
  int pixel;
  float k;
  float3 to = camera_position(&s->camera) - h->x;
  /* The merge at this vertex, the camera path's first: its radius at the camera's distance. */
  float vm = vcm_merge_factor(vcm_eta_at(radius, vcm_radius_at(radius, length(to))));
  to = normalize(to);
  float3 nf = hit_front(h), ng = hit_ng(h);
  /* Off the geometric side the camera lies on, which the shading normal must agree with. */
  if (!hit_no_leak(h, to)) return;
  if (!camera_connection(s, h->x, vcm_toward(ng, to), h->eps, &pixel, &k)) return;
  VcmF fv = vcm_eval(s, surf, h->ns, nf, to, from, to, vcm_light_eta(surf));
  float nee = KASHA_VCM_DROP_DENSITY ? 0.0f : dvcm;
  float w_light = k * spp / (KASHA_VCM_TRACING_SHARE * paths) *
                  ((merges ? vm : 0.0f) + nee + dvc * vcm_pdf(s, surf, lambert, h->ns, nf, to, from));
  k *= photon_arrival_correction(h, p->direction);
  float scale = k / (1.0f + w_light) / s->bin_nm;
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f)
    film_rows_conductor(f, p->power, 0, surf->eta_c, surf->k_c, fv.cos_m, scale * fv.conductor, rows);
#endif
  if (fv.lambert > 0.0f) {
    if (surf->passive) film_rows(f, p->power, surf->rho, 0, scale * fv.lambert, rows);
#if KASHA_FLUORESCENCE
    if (surf->fluorescent)
      film_rows(f, 0, surf->ehat, 0, spectrum_dot(KASHA_BINS, p->power, surf->a, 0) * scale * fv.lambert, rows);
#endif
  }
  if (fv.white > 0.0f) film_rows(f, p->power, 0, 0, scale * fv.white, rows);
#if KASHA_DISPERSION
  if (fv.per_bin) {
    float pdf;
    for (int i = 0; i < KASHA_BINS; ++i) {
      if (p->power[i] == 0.0f) continue;
      float v = p->power[i] * scale * rough_dielectric_eval(fv.o, fv.i, surf->eta_bins[i], surf->alpha, true, &pdf);
#if KASHA_SPECTRAL_FILM
      rows[i] += v;
#else
      for (int r = 0; r < 3; ++r) rows[r] += f->cmf[r * KASHA_BINS + i] * v;
#endif
    }
  }
#endif
  if (film_rows_finite(rows)) splat_rows(t, pixel, rows);
}
#endif

/* Light subpaths [get_global_id(0)] of the iteration's `paths`, photons as in forward transport
 * (each carrying 1/paths of the lights' power), from the stream of their index. Records past
 * `capacity` are counted but not written: the host grows the store and runs the pass again. */
__kernel void vcm_light_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, int paths, float eta_unit, float radius,
                             float per_unit, __global float* store,
                             __global int* stored, int capacity, __global int* path_last, __global ulong* film,
                             int film_shift, __global int* overflow,
                             __global float* cut, /* per path: power the depth guard cut, per its start */
                             int spp, /* camera paths a pixel */ uint seed, uint pass, int item_end) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int index = get_global_id(0);
  if (index >= item_end) return;
  /* The global radius's factors (per_unit > 0: dVM is not read, and merges count only where
   * light tracing splats). */
  const VcmRadius rad = {eta_unit, radius, per_unit};
  const float vm = vcm_merge_factor(vcm_eta_at(&rad, radius)), vc = vcm_connect_factor(vcm_eta_at(&rad, radius));
  Sampler sampler = photon_sampler(seed, pass, paths, index);
  LightOrigin o;
  Photon p = emit_photon(&s, (float)paths, &sampler, &o);
  const float3 start = p.position;
  p.position += o.normal * o.eps;
  float dvcm, dvc, dvm;
  bool far_start = false; /* from a distant or infinite light's disk: no t² at the first hit */
#if KASHA_LIGHT_SOURCES
  if (o.source) {
    /* dVCM = direct / emission, dVC = 1 / (pick · emission), 0 for a delta light (no camera
     * path hits it), as SmallVCM's GenerateLightSample. */
    const __global KLight* l = o.source;
    float direct, emission = vcm_source_emission(&s, l, p.direction, &direct);
    bool delta = l->type != KASHA_LIGHT_INFINITE;
    dvcm = direct / emission;
    dvc = delta ? 0.0f : 1.0f / (l->pick * emission);
    dvm = dvc * vc;
    far_start = !vcm_source_finite(l);
  } else
#endif
  {
    /* Emission by area and cosine, p_e = p_A cos/π; next-event estimation's pseudo-density p_A. */
    float cos_light = dot(o.normal, p.direction);
    dvcm = KASHA_PI / cos_light, dvc = KASHA_PI / o.area_pdf, dvm = dvc * vc;
  }
  SplatTarget target = {film, film_shift, 0};
  int last = -1, ordinal = 0;
  float guard = 0.0f, dvc_merge = 0.0f; /* the light side leaves its own merges out */
  bool caustic = false;                  /* it arrives from a delta bounce */
  for (int depth = 0;; ++depth) {
    if (depth == KASHA_MAX_PATH_DEPTH) {
      guard = photon_total(&p) / p.start;
      break;
    }
    HitPoint h;
    if (!intersect_scene(&s, p.position, p.direction, &h)) break;
    vcm_arrived(far_start && depth == 0 ? 1.0f : h.t, fabs(dot(h.n, p.direction)), &dvcm, &dvc, &dvm, &dvc_merge);
    /* dVCM's next-event density (SmallVCM's directPdfA, by area above) as it truly is from here. */
    if (depth == 0 && o.tri >= 0)
      dvcm *= vcm_direct_area(&s, o.tri, h.x, start, dot(o.normal, p.direction)) / o.area_pdf;
#if KASHA_SHADING_NORMALS
    /* From below the shading normal's hemisphere: the surface does not scatter it (hit_seen). */
    if (!hit_seen(&h, p.direction)) break;
#endif
    Surface surf;
    load_surface_at(&s, &h, &surf);
    float lambert = vcm_lambert_mean(&surf);
    /* A merge here is a technique (caustic merges: only from a delta bounce). */
    bool merges = vcm_mergeable(&surf) && (caustic || !KASHA_VCM_MERGE_CAUSTIC);
    float3 from = -p.direction, nf = hit_front(&h), ng = hit_ng(&h);
    if (vcm_connectible(&surf)) {
      int slot = atomic_inc(stored);
      bool kept = slot >= 0 && slot < capacity;
      __global float* r = store + (long)slot * VCM_FLOATS;
      if (kept) {
        r[0] = h.x.x, r[1] = h.x.y, r[2] = h.x.z;
        r[3] = ng.x, r[4] = ng.y, r[5] = ng.z;
        r[KASHA_PHOTON_INDEX] = as_float(index), r[KASHA_PHOTON_DEPTH] = as_float(depth);
        float arrival = photon_arrival_correction(&h, p.direction);
        for (int i = 0; i < KASHA_BINS; ++i) r[KASHA_PHOTON_POWER + i] = p.power[i] * arrival;
        __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
        m[0] = p.direction.x, m[1] = p.direction.y, m[2] = p.direction.z;
        m[3] = dvcm, m[4] = dvc, m[5] = dvm;
        m[6] = as_float(h.tri), m[7] = h.eps, m[8] = as_float(last), m[9] = as_float(ordinal);
#if KASHA_TEXTURES
        m[10] = h.b.x, m[11] = h.b.y;
#else
        m[10] = m[11] = 0.0f;
#endif
        m[12] = merges ? 1.0f : 0.0f;
        m[13] = h.ns.x, m[14] = h.ns.y, m[15] = h.ns.z;
      }
      last = slot;
      ++ordinal;
#if KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY
      if (VCM_LENGTH_COUNTS(depth + 2))
        vcm_splat(&s, &f, &target, &surf, lambert, merges, &h, from, &p, dvcm, dvc, &rad, (float)paths, spp);
#endif
    }
    int branch = scatter_photon(&p, &surf, &s, &h, &sampler, depth);
    if (branch == BRANCH_ABSORBED) break;
    bool delta = (branch == BRANCH_SPECULAR && !surface_rough(&surf)) || (branch == BRANCH_GLOSS && surf.mirror);
    caustic = delta;
    if (!vcm_scattered(&s, &surf, lambert, h.ns, nf, ng, from, p.direction, delta, KASHA_VCM_MERGE_EVERY && merges,
                       vm, vc, &dvcm, &dvc, &dvm, &dvc_merge))
      break;
  }
  path_last[index] = last;
  cut[index] = guard;
  if (target.overflow) atomic_add(overflow, target.overflow);
  add_ray_counts(&s, ray_counts);
}

/* A camera subpath: the walk (camera_walk.h) and its partial MIS weights; dvc_merge, the part of
 * dVC the merge at its merging vertex put in, until the next vertex's bounce decides whether that
 * merge makes the paths beyond (caustic merges: if that bounce is delta). */
typedef struct {
  CameraWalk w;
  float dvcm, dvc, dvm, dvc_merge;
} VcmCamera;

/* dVC for the techniques at the current vertex (next-event estimation, connections, an emitter
 * hit): with caustic merges, at the vertex after the merging one no merge makes their paths (the
 * light reaches the merging vertex from this vertex's own non-delta scattering or emission). */
inline float vcm_camera_dvc(const VcmCamera* c) {
#if KASHA_VCM_MERGE_CAUSTIC
  return fmax(c->dvc - c->dvc_merge, 0.0f);
#else
  return c->dvc;
#endif
}

/* Caustic merges: the vertex after the merging one scatters (delta or not): the merge's part of
 * dVC stays for the paths beyond only if it is delta. */
inline void vcm_camera_decide(VcmCamera* c, bool delta) {
#if KASHA_VCM_MERGE_CAUSTIC
  if (c->dvc_merge > 0.0f && !delta) c->dvc = fmax(c->dvc - c->dvc_merge, 0.0f);
#endif
  c->dvc_merge = 0.0f;
}

/* What a camera vertex's techniques share: its normals (densities and f about the shading
 * normal, turns to area about the geometric one), the Lambert mean its pseudo-densities
 * mix by, and whether it merges. */
typedef struct {
  float3 ns, nf, ng; /* shading normal on the eye's side, on the front; geometric on the eye's side */
  float lambert;
  float eta; /* a rough dielectric's index for the path (at its bin where it disperses) */
  bool merges;
} VcmVertex;

#if KASHA_VCM_CONNECT
/* Next-event estimation at a camera vertex (SmallVCM's DirectIllumination): one light point as
 * next_event.h samples it, weighed against the camera path hitting it and against every
 * technique that reaches it from the light's side. A rough dielectric takes light from either
 * side. */
inline void vcm_next_event(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                           const VcmVertex* cv, float vm, float* rows) {
  if (s->light_count == 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  float pdf_light;
  LightPoint lp = sample_light_from(s, x, v->u_light, &pdf_light);
  if (!(pdf_light > 0.0f)) return;
  float3 to = lp.position - x;
  float dist = length(to);
  if (!(dist > v->h.eps + lp.eps)) return;
  float3 wi = to / dist;
  float cos_x = fabs(dot(ns, wi)), cos_g = fabs(dot(cv->ng, wi)), cos_l = -dot(lp.normal, wi);
  if (cos_x <= 0.0f || cos_l <= 0.0f || !hit_no_leak(&v->h, wi)) return;
  VcmF fv = vcm_eval(s, surf, ns, cv->nf, eye, wi, wi, cv->eta);
  if (!vcm_f_nonzero(&fv)) return;
  float w_light, direct, emission;
#if KASHA_LIGHT_SOURCES
  if (lp.source) {
    /* cos_l is 1; a point or spot's direct density per solid angle is d² (its 1/d² in the
     * contribution); a delta light is found by nothing else. */
    const __global KLight* l = lp.source;
    emission = vcm_source_emission(s, l, -wi, &direct);
    if (vcm_source_finite(l)) direct *= dist * dist;
    w_light = lp.delta ? 0.0f : vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, wi) / (l->pick * direct);
  } else
#endif
  {
    /* The density it was sampled with (per solid angle), as the weights at the lamp's hits. */
    direct = pdf_light, emission = s->emitter_area_pdf[lp.emitter] * cos_l * KASHA_INV_PI;
    w_light = vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, wi) / direct;
  }
  /* The light part is the light point: with caustic merges no merge here or behind makes it. */
  float w_camera = emission * cos_g / (direct * cos_l) *
                   ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm : 0.0f) + c->dvcm +
                    vcm_camera_dvc(c) * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, wi, eye));
  float weight = 1.0f / (w_light + 1.0f + w_camera);
  if (segment_occluded(s, x, vcm_toward(cv->ng, wi), v->h.eps, wi, dist, lp.eps / cos_l)) return;
  float scale = cos_x / pdf_light * weight;
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  scale *= lp.scale;
#endif
  vcm_camera_apply(&c->w.p, f, surf, fv, light_point_spectrum(s, &lp), scale, rows);
}

/* A camera vertex connects to at most this many vertices of its light subpath: all of them in
 * ordinary scenes (a few a subpath), an unbiased thinning of a long one (vcm_connect). */
#define KASHA_VCM_CONNECTIONS 8

/* The surface of a stored light vertex as the light subpath met it (textures at its barycentrics,
 * a coat for its arrival), its spectra in the work item's own scratch `room` so that the camera
 * vertex's stay. *ns: the shading normal on the light's side, *nf the front one, *ng the
 * geometric one on the light's side. */
inline void vcm_light_surface(const SceneView* s, const __global float* r, __global float* room, Surface* sy,
                              float3* ns, float3* nf, float3* ng) {
  const __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
  HitPoint h;
  h.tri = as_int(m[6]);
  const __global KTriangle* t = &s->tris[h.tri];
  h.material = t->material;
  float3 arrival = (float3)(m[0], m[1], m[2]);
  *ns = (float3)(m[13], m[14], m[15]);
  *ng = (float3)(r[3], r[4], r[5]);
  float3 n = normalize(cross(load_float3(t->v1) - load_float3(t->v0), load_float3(t->v2) - load_float3(t->v0)));
  *nf = dot(n, arrival) < 0.0f ? *ns : -*ns;
#if KASHA_TEXTURES
  h.b = (float2)(m[10], m[11]);
#endif
#if KASHA_COATED
  h.cos_in = fabs(dot(n, arrival));
#endif
  SceneView own = *s;
  own.scratch = room;
  load_surface_at(&own, &h, sy);
}

/* Connections of a camera vertex to the stored vertices of its light subpath, the last stored
 * at record `last` (SmallVCM's ConnectVertices): T·f_c·G·f_l·Φ, Φ per light subpath (paths/Δλ
 * undoes the photon's 1/paths and bin width). A subpath of n > KASHA_VCM_CONNECTIONS vertices
 * (a furnace of albedo 0.999 stores a thousand) is thinned: with s = ⌈n / KASHA_VCM_CONNECTIONS⌉
 * only the vertices whose ordinal is o mod s, o uniform in [0, s) from `u`, connect, each
 * weighed s — every vertex with probability 1/s, so the sum is unbiased and a path of n camera
 * vertices costs O(n) shadow rays, not O(n²). `out` is the work item's spectra (VCM_SPECTRA):
 * f_l·Φ, then the light vertex's surface. */
inline void vcm_connect(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                        const VcmVertex* cv, float vm, float paths, const __global float* store, int last, uint u,
                        __global float* out, float* rows) {
  if (last < 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  int n = as_int(store[(long)last * VCM_FLOATS + KASHA_VCM_ORDINAL(KASHA_BINS)]) + 1;
  int stride = (n + KASHA_VCM_CONNECTIONS - 1) / KASHA_VCM_CONNECTIONS;
  int offset = (int)(u % (uint)stride);
  for (int slot = last; slot >= 0;) {
    const __global float* r = store + (long)slot * VCM_FLOATS;
    const __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
    slot = as_int(m[8]);
    if (as_int(m[9]) % stride != offset) continue;
    if (!VCM_LENGTH_COUNTS(c->w.depth + as_int(r[KASHA_PHOTON_DEPTH]) + 3)) continue;
    float3 y = (float3)(r[0], r[1], r[2]);
    float3 d = y - x;
    float dist2 = dot(d, d), dist = sqrt(dist2);
    float3 dir = d / dist;
    VcmF fc = vcm_eval(s, surf, ns, cv->nf, eye, dir, dir, cv->eta);
    if (!vcm_f_nonzero(&fc)) continue;
    if (!hit_no_leak(&v->h, dir)) continue;
    Surface sy;
    float3 ny, nfy, ngy;
    vcm_light_surface(s, r, out + KASHA_BINS, &sy, &ny, &nfy, &ngy);
    if (!vcm_no_leak(ny, ngy, -dir)) continue;
    float3 light = -(float3)(m[0], m[1], m[2]);
    VcmF fl = vcm_eval(s, &sy, ny, nfy, -dir, light, -dir, vcm_light_eta(&sy));
    if (!vcm_f_nonzero(&fl)) continue;
    /* The camera side's radiance takes the shading cosine; the turns to area, the geometric. */
    float cos_s = fabs(dot(ns, dir)), cos_c = fabs(dot(cv->ng, dir)), cos_y = fabs(dot(ngy, dir));
    float lambert_y = vcm_lambert_mean(&sy);
    bool merges_y = KASHA_VCM_MERGE_EVERY && m[12] > 0.5f; /* else behind the camera's merging vertex */
    float w_light = vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, dir) * cos_y / dist2 *
                    ((merges_y ? vm : 0.0f) + m[3] + m[4] * vcm_pdf(s, &sy, lambert_y, ny, nfy, -dir, light));
    float w_camera = vcm_pdf(s, &sy, lambert_y, ny, nfy, light, -dir) * cos_c / dist2 *
                     ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm : 0.0f) + c->dvcm +
                      vcm_camera_dvc(c) * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, dir, eye));
    float weight = 1.0f / (w_light + 1.0f + w_camera);
    if (!(weight > 0.0f)) continue;
    if (segment_occluded(s, x, vcm_toward(cv->ng, dir), v->h.eps, dir, dist, m[7] / cos_y)) continue;
    vcm_light_apply(&sy, fl, r + KASHA_PHOTON_POWER, out);
    vcm_camera_apply(&c->w.p, f, surf, fc, out, stride * weight * cos_s * cos_y / dist2 * paths / s->bin_nm, rows);
  }
}
#endif

/* Edge correction of merges (--edge-correction, on by default): a merge divides by the fraction of
 * its disc on surface it accepts (disc_coverage.h), measured with KASHA_VCM_COVERAGE_PROBES probes
 * once the merge has met a photon. The pattern's rotation is a hash of the vertex's position, so
 * the fraction is a function of the vertex and the radius alone; it tends to 1 with the radius
 * everywhere but on the edges themselves, so merges stay consistent. */
#ifndef KASHA_VCM_EDGE_CORRECTION
#define KASHA_VCM_EDGE_CORRECTION 0
#endif
#ifndef KASHA_VCM_COVERAGE_PROBES
#define KASHA_VCM_COVERAGE_PROBES 8
#endif

#if KASHA_VCM_MERGE
#if KASHA_VCM_EDGE_CORRECTION
inline float vcm_coverage(const SceneView* s, float3 x, float3 ng, float radius) {
  uint h = hash_combine(hash_combine(hash_u32(as_uint(x.x)), as_uint(x.y)), as_uint(x.z));
  float c = disc_covered(s, x, ng, radius, KASHA_GATHER_SLAB * radius, KASHA_VCM_COVERAGE_PROBES,
                         (float)h * (2.0f * KASHA_PI / 4294967296.0f));
  return c > 0.0f ? c : 1.0f; /* no probe on accepted surface: nothing to correct by */
}
#endif

/* Merges at a camera vertex (SmallVCM's RangeQuery with its MergingCallback): every stored light
 * vertex within r that merges — on the same side, facing alike and near the tangent plane of the
 * geometric surface, as photon mapping's gather — adds T·f_c·Φ weighed against the connections
 * that sample the same path (ppm: unweighted), scaled by `scale` (1/(π r² Δλ) over a branch
 * probability). */
inline void vcm_merge(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                      const VcmVertex* cv, float vc, float radius, float scale, const __global float* store,
                      const __global float4* placed, const __global int* cell_count, const __global int* cell_end,
                      float inv_cell, uint mask, float* rows) {
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  float r2 = radius * radius;
  float covered = 0.0f; /* edge correction: the disc's fraction measured at the first photon */
  int3 lo = grid_cell(x - radius, inv_cell), hi = grid_cell(x + radius, inv_cell);
  for (int cz = lo.z; cz <= hi.z; ++cz)
    for (int cy = lo.y; cy <= hi.y; ++cy)
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        uint h = grid_hash((int3)(cx, cy, cz), mask);
        int end = cell_end[h];
        for (int j = end - cell_count[h]; j < end; ++j) {
          /* The distance from the grid's own copy of the positions, in the cell's run; the
           * record only for a vertex within r. */
          float4 place = placed[j];
          float3 y = place.xyz;
          int3 own = grid_cell(y, inv_cell);
          if (own.x != cx || own.y != cy || own.z != cz) continue;
          float3 d = y - x;
          if (!(dot(d, d) < r2)) continue;
          const __global float* r = store + (long)as_int(place.w) * VCM_FLOATS;
          if (!VCM_LENGTH_COUNTS(c->w.depth + as_int(r[KASHA_PHOTON_DEPTH]) + 2)) continue;
          const __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
          if (!(m[12] > 0.5f)) continue;
          float3 ny = (float3)(r[3], r[4], r[5]);
          /* The gather's tests about the geometric surface (a shading normal tilts off the plane
           * the photons lie in: about it the slab would cut the disc). */
          float3 ng = cv->ng;
          if (dot(ny, ng) < 0.5f || fabs(dot(d, ng)) > KASHA_GATHER_SLAB * radius) continue;
          float3 light = -(float3)(m[0], m[1], m[2]);
          if (dot(light, ng) <= 0.0f) continue;
          VcmF fv = vcm_eval(s, surf, ns, cv->nf, eye, light, light, cv->eta);
#if KASHA_VCM_EDGE_CORRECTION
          if (covered == 0.0f) {
            covered = vcm_coverage(s, x, ng, radius);
            scale /= covered;
          }
#endif
#if KASHA_VCM_CONNECT
#if KASHA_VCM_MERGE_EVERY
          float dvm_light = m[5];
#else
          float dvm_light = m[4] * vc; /* a light subpath that never merges has dVM = dVC / η */
#endif
          float w_light = m[3] * vc + dvm_light * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, light);
          float w_camera = c->dvcm * vc + c->dvm * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, light, eye);
          float weight = scale / (w_light + 1.0f + w_camera);
#else
          float weight = scale;
#endif
          vcm_camera_apply(&c->w.p, f, surf, fv, r + KASHA_PHOTON_POWER, weight, rows);
        }
      }
}
#endif

/* Emission hit by the camera path (SmallVCM's GetLightRadiance): whole when seen directly or
 * through delta bounces alone, else weighed against next-event estimation and light tracing. */
inline float vcm_emission_weight(const VcmCamera* c, const SceneView* s, const HitPoint* h) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + 1)) return 0.0f;
  /* ppm: no other technique reaches an emitter (merges are taken at the first vertex that
   * merges; this path went through delta or rough ones only). */
#if KASHA_VCM_EMISSION_ONLY || !KASHA_VCM_CONNECT
  return 1.0f;
#else
  if (c->w.depth == 0) return 1.0f;
  float cos_light = dot(h->n, -c->w.dir);
  /* After a delta bounce next-event estimation could not have found it (dVCM 0). */
  float direct = c->dvcm > 0.0f ? vcm_direct_area(s, h->tri, c->w.prev_x, h->x, cos_light) : 0.0f;
  float w_camera =
      direct * c->dvcm + s->emitter_area_pdf[h->emitter] * cos_light * KASHA_INV_PI * vcm_camera_dvc(c);
  return 1.0f / (1.0f + w_camera);
#endif
}

#if KASHA_INFINITE_LIGHTS
/* A camera path that leaves the scene sees the infinite lights (SmallVCM's background in
 * GetLightRadiance): whole when seen directly, else each weighed against next-event estimation
 * of it (its direction's density, dVCM per solid angle: no hit turned it to area) and against
 * light subpaths leaving its disk. */
inline void vcm_escaped(const VcmCamera* c, const SceneView* s, const FilmView* f, float* rows) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + 1)) return;
  for (int k = 0; k < s->light_sources; ++k) {
    const __global KLight* l = &s->lights[k];
    if (l->type != KASHA_LIGHT_INFINITE) continue;
    float weight = 1.0f;
#if !KASHA_VCM_EMISSION_ONLY && KASHA_VCM_CONNECT
    if (c->w.depth > 0) {
      float direct = infinite_light_pdf(s, l, c->w.dir);
      float emission = direct / (KASHA_PI * l->radius * l->radius);
      weight = 1.0f / (1.0f + direct * c->dvcm + emission * vcm_camera_dvc(c));
    }
#endif
    pw_add(&c->w.p, f, infinite_light_spectrum(s, l, c->w.dir), 0, weight, rows);
  }
}
#endif

/* Light the camera sees directly or through delta bounces alone — a lamp, the sky, their images
 * in glass, a mirror or a smooth coat — on a walk of its own that takes only delta bounces. No
 * other technique reaches such a path (next-event estimation, connections and merges need a
 * bounce that is not delta; dVCM and dVC are 0 along it), so its MIS weight is 1 and a pixel may
 * take it from more samples than it has full camera paths: a lamp's edges and its highlight on a
 * coat converge with a pixel's samples, and these cost a ray or two, a full camera path tens. At
 * a surface that also scatters otherwise (a coat, a gloss lobe over a Lambert part) the walk
 * takes the delta lobe always, weighed by its albedo, where the full path picks it with a
 * probability: the same expectation, without the full path's rare bright picks. Bounces and
 * roulette otherwise as vcm_camera_path's. */
inline float vcm_seen_light(const SceneView* s, const FilmView* f, int pixel, Sampler* sampler, float* rows) {
  CameraWalk w;
  walk_start(&w, f, camera_position(&s->camera), camera_sample(&s->camera, pixel, sample_2d(sampler)));
  CameraVertex v;
  while (w.depth < KASHA_MAX_PATH_DEPTH) {
    HitPoint* h = &v.h;
    if (!intersect_scene(s, w.org, w.dir, h)) {
#if KASHA_INFINITE_LIGHTS
      if (VCM_LENGTH_COUNTS(w.depth + 1)) walk_escaped(&w, s, f, rows); /* whole: w.specular */
#endif
      return 0.0f;
    }
    if (h->emitter >= 0 && h->front && VCM_LENGTH_COUNTS(w.depth + 1)) {
      float weight = 1.0f;
#if KASHA_EMISSION_TEXTURES
      weight *= emission_factor(s, h->tri, h->b.x, h->b.y);
#endif
      pw_add(&w.p, f, emitter_spectrum(s, h->emitter), 0, weight, rows);
    }
#if KASHA_SHADING_NORMALS
    if (!hit_seen(h, w.dir)) return 0.0f;
#endif
    load_surface_at(s, h, &v.surf);
    if (surface_rough(&v.surf)) return 0.0f;
    sampler_at(sampler, 1 + w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
    v.u_choice = sample_2d(sampler);
    v.u_light = sample_2d(sampler);
    v.u_dir = sample_2d(sampler);
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf)) {
      if (!walk_specular(&w, f, &v)) return 0.0f;
    } else
#endif
    {
      if (!(v.surf.g > 0.0f && v.surf.mirror)) return 0.0f;
      w.dir = reflect_dir(w.dir, h->ns);
      pw_scatter_diagonal(&w.p, 0, v.surf.g);
    }
    if (!walk_on(&w, f, &v)) return 0.0f;
  }
  return walk_cut(&w, f);
}

/* One camera path of the iteration, one of `spp` the pixel has, with light subpath `partner`.
 * `own`: that subpath is in the store (the chunk holding it): emission, next-event estimation and
 * connections count then; merges count with every chunk. `seen_apart`: vcm_seen_light takes the
 * light reached through delta bounces alone, so this path leaves it out. Returns what it still
 * carried (relative to its start) if the depth guard cut it. */
inline float vcm_camera_path(const SceneView* s, const FilmView* f, int pixel, int spp, int partner, Sampler* sampler,
                             float paths, VcmRadius radius, const __global float* store,
                             const __global int* path_last, const __global float4* placed,
                             const __global int* cell_count, const __global int* cell_end, float inv_cell, uint mask,
                             bool own, bool seen_apart, uint seed, __global float* out, float* rows) {
  /* The factors of the global radius; where the radius is the path's, of its merging vertex's. */
  float r_merge = radius.radius;
  float vm = vcm_merge_factor(vcm_eta_at(&radius, r_merge)), vc = vcm_connect_factor(vcm_eta_at(&radius, r_merge));
  float travelled = 0.0f;
  VcmCamera c;
  float3 dir = camera_sample(&s->camera, pixel, sample_2d(sampler));
  walk_start(&c.w, f, camera_position(&s->camera), dir);
  {
    /* The camera's density of the direction per solid angle, for one of the pixel's spp samples
     * (dVCM: light subpaths over camera paths, as SmallVCM's with one camera path a pixel). */
    const KCamera* k = &s->camera;
    float3 forward = normalize((float3)(k->forward[0], k->forward[1], k->forward[2]));
    float pixel_area = 4.0f * length((float3)(k->right[0], k->right[1], k->right[2])) *
                       length((float3)(k->up[0], k->up[1], k->up[2])) / (float)(k->width * k->height);
    float cos_c = dot(dir, forward);
    c.dvcm = KASHA_VCM_TRACING_SHARE * paths / spp * pixel_area * cos_c * cos_c * cos_c;
    c.dvc = c.dvm = c.dvc_merge = 0.0f;
  }
  CameraVertex v;
  bool met = false;       /* a vertex that is not delta is behind */
  bool delta_only = true; /* every bounce so far was delta (vcm_seen_light's paths) */
  while (c.w.depth < KASHA_MAX_PATH_DEPTH) {
    HitPoint* h = &v.h;
    if (!intersect_scene(s, c.w.org, c.w.dir, h)) {
#if KASHA_INFINITE_LIGHTS
      if (own && !(seen_apart && delta_only)) vcm_escaped(&c, s, f, rows);
#endif
      return 0.0f;
    }
    vcm_arrived(h->t, fabs(dot(h->n, c.w.dir)), &c.dvcm, &c.dvc, &c.dvm, &c.dvc_merge);
    travelled += h->t;
    if (own && h->emitter >= 0 && h->front && !(seen_apart && delta_only)) {
      float weight = vcm_emission_weight(&c, s, h);
#if KASHA_EMISSION_TEXTURES
      weight *= emission_factor(s, h->tri, h->b.x, h->b.y);
#endif
      pw_add(&c.w.p, f, emitter_spectrum(s, h->emitter), 0, weight, rows);
    }
#if KASHA_SHADING_NORMALS
    /* Seen from below the shading normal's hemisphere, the surface scatters nothing (hit_seen). */
    if (!hit_seen(h, c.w.dir)) return 0.0f;
#endif
    load_surface_at(s, h, &v.surf);
    v.probs = surface_specular(&v.surf) ? (float3)(1.0f, 0.0f, 0.0f) : branch_probabilities(&c.w.p, f, &v.surf);
    if (v.probs.x + v.probs.y + v.probs.z <= 0.0f) return 0.0f;
    sampler_at(sampler, 1 + c.w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
    v.u_choice = sample_2d(sampler);
    v.u_light = sample_2d(sampler);
    v.u_dir = sample_2d(sampler);
    float3 eye = -c.w.dir;
    VcmVertex cv;
    cv.ns = h->ns;
    cv.nf = hit_front(h);
    cv.ng = hit_ng(h);
    cv.lambert = vcm_lambert_mean(&v.surf);
    /* Merging here: a vertex whose material merges, and (--merges first) no vertex before it that
     * is not delta (ppm merges once, at the first that merges). */
#if KASHA_VCM_MERGE_EVERY || !KASHA_VCM_CONNECT
    cv.merges = vcm_mergeable(&v.surf);
#else
    cv.merges = vcm_mergeable(&v.surf) && !met;
#endif
    met = met || vcm_connectible(&v.surf);
    if (cv.merges && radius.per_unit > 0.0f) {
      r_merge = vcm_radius_at(&radius, travelled);
      vm = vcm_merge_factor(vcm_eta_at(&radius, r_merge));
      vc = vcm_connect_factor(vcm_eta_at(&radius, r_merge));
    }
    bool rough = surface_rough(&v.surf);
    cv.eta = 1.0f;
#if KASHA_ROUGH && KASHA_DIELECTRIC
    /* A rough dielectric's index, a dispersive one's at the path's bin (chosen here on the
     * vertex's fourth sample pair if the path has none, as walk_rough does). */
    if (rough && v.surf.kind == KASHA_KIND_DIELECTRIC) {
      cv.eta = walk_eta(&c.w, f, &v.surf, sample_2d(sampler).x);
      if (cv.eta < 0.0f) return 0.0f;
    }
#endif
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf) && !rough) {
      if (!walk_specular(&c.w, f, &v)) return 0.0f;
      vcm_camera_decide(&c, true);
      vcm_scattered(s, &v.surf, 0.0f, h->ns, cv.nf, cv.ng, eye, c.w.dir, true, false, vm, vc, &c.dvcm, &c.dvc,
                    &c.dvm, &c.dvc_merge);
      if (!walk_on(&c.w, f, &v)) return 0.0f;
      continue;
    }
#endif
    if (vcm_connectible(&v.surf) && !KASHA_VCM_EMISSION_ONLY) {
#if KASHA_VCM_CONNECT
      if (own) {
        if (VCM_LENGTH_COUNTS(c.w.depth + 2)) vcm_next_event(&c, s, f, &v, &cv, vm, rows);
        vcm_connect(&c, s, f, &v, &cv, vm, paths, store, path_last[partner],
                    hash_combine(hash_combine(seed, (uint)partner), (uint)c.w.depth), out, rows);
      }
#if KASHA_VCM_MERGE
      if (cv.merges)
        vcm_merge(&c, s, f, &v, &cv, vc, r_merge, KASHA_INV_PI / (r_merge * r_merge * s->bin_nm), store, placed,
                  cell_count, cell_end, inv_cell, mask, rows);
#endif
#else
      /* ppm: the first vertex that merges merges all of it, unless a mirror lobe chosen by its
       * probability carries the path on. */
      float p_mirror = v.surf.mirror && !surface_specular(&v.surf) ? v.probs.x : 0.0f;
      if (cv.merges && !(v.u_choice.x < p_mirror)) {
        vcm_merge(&c, s, f, &v, &cv, vc, r_merge, KASHA_INV_PI / (r_merge * r_merge * s->bin_nm) / (1.0f - p_mirror),
                  store, placed, cell_count, cell_end, inv_cell, mask, rows);
        return 0.0f;
      }
#endif
    }
#if KASHA_ROUGH
    if (rough) {
      /* A rough interface: its direction from the visible normals (walk_rough_scatter). */
      if (!walk_rough_scatter(&c.w, &v, cv.eta)) return 0.0f;
    } else
#endif
    {
      float3 probs = v.probs;
      float choice = v.u_choice.x;
      if (choice < probs.x) {
        if (!walk_gloss(&c.w, s, &v, sampler)) return 0.0f;
      } else if (choice < probs.x + probs.y || probs.z <= 0.0f) {
        lambert_bounce(&c.w, &v, probs.y);
        pw_scatter_diagonal(&c.w.p, v.surf.rho, lambert_weight(&c.w, &v) / probs.y);
#if KASHA_FLUORESCENCE
      } else {
        lambert_bounce(&c.w, &v, probs.z);
        pw_scatter_fluorescent(&c.w.p, f, v.surf.ehat, v.surf.a, lambert_weight(&c.w, &v) / probs.z);
#if KASHA_DISPERSION
        c.w.bin = -1; /* re-emission spreads the path over the excitation spectrum again */
#endif
#endif
      }
    }
    vcm_camera_decide(&c, c.w.specular);
    if (!vcm_scattered(s, &v.surf, cv.lambert, h->ns, cv.nf, cv.ng, eye, c.w.dir, c.w.specular, cv.merges, vm, vc,
                       &c.dvcm, &c.dvc, &c.dvm, &c.dvc_merge))
      return 0.0f;
    delta_only = delta_only && c.w.specular;
    if (!walk_on(&c.w, f, &v)) return 0.0f;
  }
  return walk_cut(&c.w, f);
}

/* `spp` camera paths a pixel, sample j's light subpath (pixel · spp + j) modulo `paths`, their
 * estimates with the store's chunk of light subpaths [chunk_first, chunk_end) added to the pixel's
 * sums: the same paths (the same random numbers) with every chunk. `path_spectra`: VCM_SPECTRA
 * floats per work item for a light vertex's f·Φ and surface. */
__kernel void vcm_camera_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, int paths, int chunk_first, int chunk_end,
                              float eta_unit, float radius, float per_unit,
                              __global const float* store, __global const int* path_last,
                              __global const float4* placed, __global const int* cell_count,
                              __global const int* cell_end, float inv_cell, uint mask, __global float* path_spectra,
                              __global float* sums, __global int* rejected, __global float* cut, int spp,
                              __global const int* seen_pixels, int seen_samples, uint seed, uint pass,
                              int item_end) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int pixel = launch_pixel(&s.camera, item_end);
  if (pixel < 0) return;
  /* The pixel's stream: a seed apart from the light subpaths'. */
  Sampler sampler = sampler_start(seed ^ 0x5bd1e995u, (uint)pixel, 0, pass, (uint)pixel);
  __global float* out = path_spectra + (long)(get_global_id(0) - get_global_offset(0)) * VCM_SPECTRA;
  float guard = 0.0f;
  int bad = 0;
  bool owned = false;
  /* The light seen through delta bounces alone, in the pixels the host found it in
   * (seen_pixels), from `seen_samples` samples per camera path, each index of their own stream a
   * point of one Sobol sequence; elsewhere the camera paths take it. */
  int seen = seen_pixels[pixel] ? seen_samples : 0;
  Sampler seen_sampler = sampler_start(seed ^ 0x7f4a7c15u, (uint)pixel, 0, pass, (uint)pixel);
  for (int j = 0; j < spp; ++j) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)j);
    float rows[KASHA_FILM_ROWS];
    film_rows_clear(rows);
    int partner = (int)(((long)pixel * spp + j) % paths);
    bool own = partner >= chunk_first && partner < chunk_end;
    VcmRadius rad = {eta_unit, radius, per_unit};
    float g = vcm_camera_path(&s, &f, pixel, spp, partner, &sampler, (float)paths, rad, store, path_last,
                              placed, cell_count, cell_end, inv_cell, mask, own, seen > 0,
                              hash_combine(seed ^ 0x2545f491u, pass), out, rows);
    if (own && seen > 0) {
      float seen_rows[KASHA_FILM_ROWS], seen_cut = 0.0f;
      film_rows_clear(seen_rows);
      for (int k = 0; k < seen; ++k) {
        sampler_next_sample(&seen_sampler, (pass * (uint)spp + (uint)j) * (uint)seen + (uint)k);
        seen_cut += vcm_seen_light(&s, &f, pixel, &seen_sampler, seen_rows);
      }
      for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] += seen_rows[r] / (float)seen;
      guard += seen_cut / (float)seen; /* the depth guard's tally: a camera path's share */
    }
    if (own) guard += g, owned = true;
    if (film_rows_finite(rows))
      film_add(sums, pixel, rows);
    else
      ++bad;
  }
  if (owned) cut[pixel] += guard;
  rejected[pixel] += bad;
  add_ray_counts(&s, ray_counts);
}
