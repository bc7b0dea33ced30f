/* Vertex connection and merging (docs/integrators.md#vertex-connection-and-merging): Georgiev,
 * Křivánek, Davidovič and Slusallek 2012, as SmallVCM's vertexcm.hxx lays it out, with kasha's
 * transport — light subpaths are spectral photons (photon_transport.h: fluorescent re-emission,
 * constant-energy branching), camera subpaths carry a diagonal or rank-1 colour (path_weight.h),
 * so a connection T·f·G·f·Φ and a merge T·f·Φ cost O(N) and never pair wavelengths.
 *
 * An iteration is two launches and a grid:
 * 1. vcm_light_pass: light subpaths (one per pixel, at least 2^14); each vertex with a non-delta part is stored
 *    (vcm_layout.h), linked to its path's previous one, and (connecting modes) splatted to the
 *    camera, MIS-weighted;
 * 2. the hashed grid over the stored vertices (hash_grid.cl; merging modes), cells of 2r;
 * 3. vcm_camera_pass: one camera path per pixel; at each vertex with a non-delta part, emission
 *    hit, next-event estimation, connections to its light subpath's vertices (connecting modes)
 *    and merges with the stored vertices within r (merging modes), each MIS-weighted.
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

#include "camera.h"
#include "camera_splat.h"
#include "camera_walk.h"
#include "hash_grid.cl"
#include "photon_transport.h"

#ifndef KASHA_VCM_CONNECT
#define KASHA_VCM_CONNECT 1
#endif
#ifndef KASHA_VCM_MERGE
#define KASHA_VCM_MERGE 1
#endif

#define VCM_FLOATS KASHA_VCM_FLOATS(KASHA_BINS)

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

/* The MIS factors of an iteration with merging radius r and L light subpaths, η = π r² L
 * (SmallVCM's mMisVmWeightFactor and mMisVcWeightFactor): a merge weighs η against a
 * connection's 1, a connection 1/η against a merge; 0 for a technique the mode leaves out. */
inline float vcm_merge_factor(float eta) { return KASHA_VCM_MERGE ? eta : 0.0f; }
inline float vcm_connect_factor(float eta) { return KASHA_VCM_CONNECT ? 1.0f / eta : 0.0f; }

/* A vertex connects and merges where its surface has a non-delta part: a Lambert part or a
 * tabulated gloss lobe (mirrors, smooth glass and metal are delta: neither). */
inline bool vcm_connectible(const Surface* surf) {
  if (surface_specular(surf)) return false;
  return surface_has_lambert(surf) || (surf->g > 0.0f && !surf->mirror);
}

/* The gloss part's share of the pseudo-density: g against the Lambert parts' mean reflectance
 * and excitation, from the material alone, so both subpaths find the same density at a vertex. */
inline float vcm_gloss_share(const Surface* surf) {
  if (!(surf->g > 0.0f)) return 0.0f;
  float lambert = 0.0f;
  if (surf->passive)
    for (int i = 0; i < KASHA_BINS; ++i) lambert += surf->rho[i];
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) lambert += surf->a_sum;
#endif
  lambert /= KASHA_BINS;
  return surf->g / (surf->g + lambert);
}

/* The pseudo-density (per solid angle) of leaving the vertex along `to` having arrived from
 * `from` (both pointing away from the surface, ns on from's side): the Lambert parts' cosine and
 * the tabulated lobe, mixed by the gloss share; a mirror's delta part is not in it. */
inline float vcm_pdf(const SceneView* s, const Surface* surf, float share, float3 ns, float3 from, float3 to) {
  float c = dot(ns, to);
  if (c <= 0.0f) return 0.0f;
  float pdf = (1.0f - share) * c * KASHA_INV_PI;
#if KASHA_GLOSS
  if (share > 0.0f && !surf->mirror) pdf += share * lobe_pdf(surf->m, s->lobes, dot(to, reflect_dir(-from, ns)));
#endif
  return pdf;
}

/* out = f(eye, light)·phi at a light vertex, f's non-delta parts without the cosine: light
 * arriving from `light` leaves towards `eye` (Lambert, fluorescent re-emission ê (a·Φ)/π, lobe). */
inline void vcm_light_scatter(const SceneView* s, const Surface* surf, float3 ns, float3 light, float3 eye,
                              const __global float* phi, __global float* out) {
  float fg = 0.0f, fl = 0.0f;
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) fg = surf->g * lobe_brdf(surf->m, s->lobes, eye, light, ns);
#endif
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) fl = spectrum_dot(KASHA_BINS, 0, surf->a, phi) * KASHA_INV_PI;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * KASHA_INV_PI + fg) + surf->ehat[i] * fl;
#else
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * KASHA_INV_PI + fg);
#endif
}

/* rows += scale · T·f(eye, light)·spectrum at a camera vertex, f's non-delta parts without the
 * cosine (next_event.h's terms, with any spectrum). */
inline void vcm_camera_scatter(const PathWeight* p, const FilmView* f, const SceneView* s, const Surface* surf,
                               float3 ns, float3 eye, float3 light, const __global float* spectrum, float scale,
                               float* rows) {
  if (surf->passive) pw_add(p, f, surf->rho, spectrum, scale * KASHA_INV_PI, rows);
#if KASHA_FLUORESCENCE
  if (surf->fluorescent)
    pw_add(p, f, surf->ehat, 0, scale * KASHA_INV_PI * spectrum_dot(KASHA_BINS, 0, surf->a, spectrum), rows);
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) {
    float fg = lobe_brdf(surf->m, s->lobes, eye, light, ns);
    if (fg > 0.0f) pw_add(p, f, spectrum, 0, scale * surf->g * fg, rows);
  }
#endif
}

/* A subpath's partial MIS weights after its vertex scattered it from `from` to `to` (SmallVCM's
 * SampleScattering): a delta bounce keeps them but for the cosine; any other divides by the
 * pseudo-density of the direction and carries the reverse one. False: no density, the path ends. */
inline bool vcm_scattered(const SceneView* s, const Surface* surf, float share, float3 ns, float3 from, float3 to,
                          bool delta, float vm, float vc, float* dvcm, float* dvc, float* dvm) {
  float cos_out = fabs(dot(ns, to));
  if (delta) {
    *dvcm = 0.0f;
    *dvc *= cos_out;
    *dvm *= cos_out;
    return true;
  }
  float pdf = vcm_pdf(s, surf, share, ns, from, to), rev = vcm_pdf(s, surf, share, ns, to, from);
  if (!(pdf > 0.0f)) return false;
  *dvc = cos_out / pdf * (*dvc * rev + *dvcm + vm);
  *dvm = cos_out / pdf * (*dvm * rev + *dvcm * vc + 1.0f);
  *dvcm = 1.0f / pdf;
  return true;
}

/* Arriving at a hit at distance t, cosine cos_in: the weights turn from solid angle to area. */
inline void vcm_arrived(float t, float cos_in, float* dvcm, float* dvc, float* dvm) {
  *dvcm *= t * t / cos_in;
  *dvc /= cos_in;
  *dvm /= cos_in;
}

#if KASHA_VCM_CONNECT
/* A light vertex seen by the camera (light tracing, SmallVCM's ConnectToCamera): f Φ k / Δλ with
 * k = cos · importance (camera_connection), which is also the camera's density of the vertex per
 * area, weighed against every technique that samples it from the camera side. */
inline void vcm_splat(const SceneView* s, const FilmView* f, SplatTarget* t, const Surface* surf, float share,
                      const HitPoint* h, float3 from, const Photon* p, float dvcm, float dvc, float vm,
                      float paths) {
  int pixel;
  float k;
  if (!camera_connection(s, h->x, h->ns, h->eps, &pixel, &k)) return;
  float3 to = normalize(camera_position(&s->camera) - h->x);
  float nee = KASHA_VCM_DROP_DENSITY ? 0.0f : dvcm;
  float w_light = k / paths * (vm + nee + dvc * vcm_pdf(s, surf, share, h->ns, to, from));
  float scale = k / (1.0f + w_light) / s->bin_nm;
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  if (surf->passive) film_rows(f, p->power, surf->rho, 0, scale * KASHA_INV_PI, rows);
#if KASHA_FLUORESCENCE
  if (surf->fluorescent)
    film_rows(f, 0, surf->ehat, 0, spectrum_dot(KASHA_BINS, p->power, surf->a, 0) * scale * KASHA_INV_PI, rows);
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) {
    float fg = lobe_brdf(surf->m, s->lobes, to, from, h->ns);
    if (fg > 0.0f) film_rows(f, p->power, 0, 0, surf->g * fg * scale, rows);
  }
#endif
  if (film_rows_finite(rows)) splat_rows(t, pixel, rows);
}
#endif

/* Light subpaths [get_global_id(0)] of the iteration's `paths`, photons as in forward transport
 * (each carrying 1/paths of the lights' power), from the stream of their index. Records past
 * `capacity` are counted but not written: the host grows the store and runs the pass again. */
__kernel void vcm_light_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, int paths, float eta, __global float* store,
                             __global int* stored, int capacity, __global int* path_last, __global ulong* film,
                             int film_shift, __global int* overflow,
                             __global float* cut, /* per path: power the depth guard cut, per its start */
                             uint seed, uint pass, int item_end) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int index = get_global_id(0);
  if (index >= item_end) return;
  const float vm = vcm_merge_factor(eta), vc = vcm_connect_factor(eta);
  Sampler sampler = photon_sampler(seed, pass, paths, index);
  LightOrigin o;
  Photon p = emit_photon(&s, (float)paths, &sampler, &o);
  p.position += o.normal * o.eps;
  /* Emission by area and cosine, p_e = p_A cos/π; next-event estimation's pseudo-density p_A. */
  float cos_light = dot(o.normal, p.direction);
  float dvcm = KASHA_PI / cos_light, dvc = KASHA_PI / o.area_pdf, dvm = dvc * vc;
  SplatTarget target = {film, film_shift, 0};
  int last = -1, ordinal = 0;
  float guard = 0.0f;
  for (int depth = 0;; ++depth) {
    if (depth == KASHA_MAX_PATH_DEPTH) {
      guard = photon_total(&p) / p.start;
      break;
    }
    HitPoint h;
    if (!intersect_scene(&s, p.position, p.direction, &h)) break;
    vcm_arrived(h.t, fabs(dot(h.n, p.direction)), &dvcm, &dvc, &dvm);
    Surface surf;
    load_surface_at(&s, &h, &surf);
    float share = vcm_gloss_share(&surf);
    float3 from = -p.direction;
    if (vcm_connectible(&surf)) {
      int slot = atomic_inc(stored);
      if (slot >= 0 && slot < capacity) {
        __global float* r = store + (long)slot * VCM_FLOATS;
        r[0] = h.x.x, r[1] = h.x.y, r[2] = h.x.z;
        r[3] = h.ns.x, r[4] = h.ns.y, r[5] = h.ns.z;
        r[KASHA_PHOTON_INDEX] = as_float(index), r[KASHA_PHOTON_DEPTH] = as_float(depth);
        for (int i = 0; i < KASHA_BINS; ++i) r[KASHA_PHOTON_POWER + i] = p.power[i];
        __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
        m[0] = p.direction.x, m[1] = p.direction.y, m[2] = p.direction.z;
        m[3] = dvcm, m[4] = dvc, m[5] = dvm;
        m[6] = as_float(h.material), m[7] = h.eps, m[8] = as_float(last), m[9] = as_float(ordinal);
      }
      last = slot;
      ++ordinal;
#if KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY
      if (VCM_LENGTH_COUNTS(depth + 2))
        vcm_splat(&s, &f, &target, &surf, share, &h, from, &p, dvcm, dvc, vm, (float)paths);
#endif
    }
    int branch = scatter_photon(&p, &surf, &s, &h, &sampler, depth);
    if (branch == BRANCH_ABSORBED) break;
    bool delta = branch == BRANCH_SPECULAR || (branch == BRANCH_GLOSS && surf.mirror);
    if (!vcm_scattered(&s, &surf, share, h.ns, from, p.direction, delta, vm, vc, &dvcm, &dvc, &dvm)) break;
  }
  path_last[index] = last;
  cut[index] = guard;
  if (target.overflow) atomic_add(overflow, target.overflow);
  add_ray_counts(&s, ray_counts);
}

/* A camera subpath: the walk (camera_walk.h) and its partial MIS weights. */
typedef struct {
  CameraWalk w;
  float dvcm, dvc, dvm;
} VcmCamera;

#if KASHA_VCM_CONNECT
/* Next-event estimation at a camera vertex (SmallVCM's DirectIllumination): one light point as
 * next_event.h samples it, weighed against the camera path hitting it and against every
 * technique that reaches it from the light's side. */
inline void vcm_next_event(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                           float share, float vm, float* rows) {
  if (s->light_count == 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = v->h.ns, eye = -c->w.dir;
  float pdf_light;
  LightPoint lp = sample_light_from(s, x, v->u_light, &pdf_light);
  if (!(pdf_light > 0.0f)) return;
  float3 to = lp.position - x;
  float dist = length(to);
  if (!(dist > v->h.eps + lp.eps)) return;
  float3 wi = to / dist;
  float cos_x = dot(ns, wi), cos_l = -dot(lp.normal, wi);
  if (cos_x <= 0.0f || cos_l <= 0.0f) return;
  float area = s->emitter_area_pdf[lp.emitter];
  float direct = area * dist * dist / cos_l, emission = area * cos_l * KASHA_INV_PI;
  float w_light = vcm_pdf(s, surf, share, ns, eye, wi) / direct;
  float w_camera = emission * cos_x / (direct * cos_l) * (vm + c->dvcm + c->dvc * vcm_pdf(s, surf, share, ns, wi, eye));
  float weight = 1.0f / (w_light + 1.0f + w_camera);
  if (segment_occluded(s, x, ns, v->h.eps, wi, dist, lp.eps / cos_l)) return;
  vcm_camera_scatter(&c->w.p, f, s, surf, ns, eye, wi, light_point_spectrum(s, &lp), cos_x / pdf_light * weight,
                     rows);
}

/* A camera vertex connects to at most this many vertices of its light subpath: all of them in
 * ordinary scenes (a few a subpath), an unbiased thinning of a long one (vcm_connect). */
#define KASHA_VCM_CONNECTIONS 8

/* Connections of a camera vertex to the stored vertices of its light subpath, the last stored
 * at record `last` (SmallVCM's ConnectVertices): T·f_c·G·f_l·Φ, Φ per light subpath (paths/Δλ
 * undoes the photon's 1/paths and bin width). A subpath of n > KASHA_VCM_CONNECTIONS vertices
 * (a furnace of albedo 0.999 stores a thousand) is thinned: with s = ⌈n / KASHA_VCM_CONNECTIONS⌉
 * only the vertices whose ordinal is o mod s, o uniform in [0, s) from `u`, connect, each
 * weighed s — every vertex with probability 1/s, so the sum is unbiased and a path of n camera
 * vertices costs O(n) shadow rays, not O(n²). `out` is the work item's spectrum for f_l·Φ. */
inline void vcm_connect(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v, float share,
                        float vm, float paths, const __global float* store, int last, uint u, __global float* out,
                        float* rows) {
  if (last < 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = v->h.ns, eye = -c->w.dir;
  int n = as_int(store[(long)last * VCM_FLOATS + KASHA_VCM_ORDINAL(KASHA_BINS)]) + 1;
  int stride = (n + KASHA_VCM_CONNECTIONS - 1) / KASHA_VCM_CONNECTIONS;
  int offset = (int)(u % (uint)stride);
  for (int slot = last; slot >= 0;) {
    const __global float* r = store + (long)slot * VCM_FLOATS;
    const __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
    slot = as_int(m[8]);
    if (as_int(m[9]) % stride != offset) continue;
    if (!VCM_LENGTH_COUNTS(c->w.depth + as_int(r[KASHA_PHOTON_DEPTH]) + 3)) continue;
    float3 y = (float3)(r[0], r[1], r[2]), ny = (float3)(r[3], r[4], r[5]);
    float3 d = y - x;
    float dist2 = dot(d, d), dist = sqrt(dist2);
    float3 dir = d / dist;
    float cos_c = dot(ns, dir), cos_y = -dot(ny, dir);
    if (!(cos_c > 0.0f && cos_y > 0.0f)) continue;
    Surface sy;
    load_surface(s, as_int(m[6]), &sy);
    float share_y = vcm_gloss_share(&sy);
    float3 light = -(float3)(m[0], m[1], m[2]);
    float w_light = vcm_pdf(s, surf, share, ns, eye, dir) * cos_y / dist2 *
                    (vm + m[3] + m[4] * vcm_pdf(s, &sy, share_y, ny, -dir, light));
    float w_camera = vcm_pdf(s, &sy, share_y, ny, light, -dir) * cos_c / dist2 *
                     (vm + c->dvcm + c->dvc * vcm_pdf(s, surf, share, ns, dir, eye));
    float weight = 1.0f / (w_light + 1.0f + w_camera);
    if (!(weight > 0.0f)) continue;
    if (segment_occluded(s, x, ns, v->h.eps, dir, dist, m[7] / cos_y)) continue;
    vcm_light_scatter(s, &sy, ny, light, -dir, r + KASHA_PHOTON_POWER, out);
    vcm_camera_scatter(&c->w.p, f, s, surf, ns, eye, dir, out,
                       stride * weight * cos_c * cos_y / dist2 * paths / s->bin_nm, rows);
  }
}
#endif

#if KASHA_VCM_MERGE
/* Merges at a camera vertex (SmallVCM's RangeQuery with its MergingCallback): every stored light
 * vertex within r — on the same side, facing alike and near the tangent plane, as photon
 * mapping's gather — adds T·f_c·Φ weighed against the connections that sample the same path
 * (ppm: unweighted), scaled by `scale` (1/(π r² Δλ) over a branch probability). */
inline void vcm_merge(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v, float share,
                      float vc, float radius, float scale, const __global float* store, const __global int* sorted,
                      const __global int* cell_count, const __global int* cell_end, float inv_cell, uint mask,
                      float* rows) {
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = v->h.ns, eye = -c->w.dir;
  float r2 = radius * radius;
  int3 lo = grid_cell(x - radius, inv_cell), hi = grid_cell(x + radius, inv_cell);
  for (int cz = lo.z; cz <= hi.z; ++cz)
    for (int cy = lo.y; cy <= hi.y; ++cy)
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        uint h = grid_hash((int3)(cx, cy, cz), mask);
        int end = cell_end[h];
        for (int j = end - cell_count[h]; j < end; ++j) {
          const __global float* r = store + (long)sorted[j] * VCM_FLOATS;
          float3 y = record_position(r);
          int3 own = grid_cell(y, inv_cell);
          if (own.x != cx || own.y != cy || own.z != cz) continue;
          if (!VCM_LENGTH_COUNTS(c->w.depth + as_int(r[KASHA_PHOTON_DEPTH]) + 2)) continue;
          float3 d = y - x;
          if (!(dot(d, d) < r2)) continue;
          float3 ny = (float3)(r[3], r[4], r[5]);
          if (dot(ny, ns) < 0.5f || fabs(dot(d, ns)) > KASHA_GATHER_SLAB * radius) continue;
          const __global float* m = r + KASHA_VCM_ARRIVAL(KASHA_BINS);
          float3 light = -(float3)(m[0], m[1], m[2]);
          if (dot(light, ns) <= 0.0f) continue;
#if KASHA_VCM_CONNECT
          float w_light = m[3] * vc + m[5] * vcm_pdf(s, surf, share, ns, eye, light);
          float w_camera = c->dvcm * vc + c->dvm * vcm_pdf(s, surf, share, ns, light, eye);
          float weight = 1.0f / (w_light + 1.0f + w_camera);
#else
          float weight = 1.0f;
#endif
          vcm_camera_scatter(&c->w.p, f, s, surf, ns, eye, light, r + KASHA_PHOTON_POWER, weight * scale, rows);
        }
      }
}
#endif

/* Emission hit by the camera path (SmallVCM's GetLightRadiance): whole when seen directly or
 * through delta bounces alone, else weighed against next-event estimation and light tracing. */
inline float vcm_emission_weight(const VcmCamera* c, const SceneView* s, const HitPoint* h) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + 1)) return 0.0f;
  if (c->w.depth == 0 || KASHA_VCM_EMISSION_ONLY) return 1.0f;
  float area = s->emitter_area_pdf[h->emitter];
  float w_camera = area * c->dvcm + area * dot(h->n, -c->w.dir) * KASHA_INV_PI * c->dvc;
  return 1.0f / (1.0f + w_camera);
}

/* One camera path of the iteration. `own`: its light subpath is in the store (the chunk holding
 * it): emission, next-event estimation and connections count then; merges count with every
 * chunk. Returns what it still carried (relative to its start) if the depth guard cut it. */
inline float vcm_camera_path(const SceneView* s, const FilmView* f, int pixel, Sampler* sampler, float paths,
                             float eta, float radius, const __global float* store, const __global int* path_last,
                             const __global int* sorted, const __global int* cell_count,
                             const __global int* cell_end, float inv_cell, uint mask, bool own, uint seed,
                             __global float* out, float* rows) {
  const float vm = vcm_merge_factor(eta), vc = vcm_connect_factor(eta);
  VcmCamera c;
  float3 dir = camera_sample(&s->camera, pixel, sample_2d(sampler));
  walk_start(&c.w, f, camera_position(&s->camera), dir);
  {
    /* The camera's density of the direction per solid angle, for one pixel's sample. */
    const KCamera* k = &s->camera;
    float3 forward = normalize((float3)(k->forward[0], k->forward[1], k->forward[2]));
    float pixel_area = 4.0f * length((float3)(k->right[0], k->right[1], k->right[2])) *
                       length((float3)(k->up[0], k->up[1], k->up[2])) / (float)(k->width * k->height);
    float cos_c = dot(dir, forward);
    c.dvcm = paths * pixel_area * cos_c * cos_c * cos_c;
    c.dvc = c.dvm = 0.0f;
  }
  CameraVertex v;
  while (c.w.depth < KASHA_MAX_PATH_DEPTH) {
    HitPoint* h = &v.h;
    if (!intersect_scene(s, c.w.org, c.w.dir, h)) return 0.0f;
    vcm_arrived(h->t, fabs(dot(h->n, c.w.dir)), &c.dvcm, &c.dvc, &c.dvm);
    if (own && h->emitter >= 0 && h->front)
      pw_add(&c.w.p, f, emitter_spectrum(s, h->emitter), 0, vcm_emission_weight(&c, s, h), rows);
    load_surface_at(s, h, &v.surf);
    v.probs = surface_specular(&v.surf) ? (float3)(1.0f, 0.0f, 0.0f) : branch_probabilities(&c.w.p, f, &v.surf);
    if (v.probs.x + v.probs.y + v.probs.z <= 0.0f) return 0.0f;
    sampler_at(sampler, 1 + c.w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
    v.u_choice = sample_2d(sampler);
    v.u_light = sample_2d(sampler);
    v.u_dir = sample_2d(sampler);
    float3 eye = -c.w.dir;
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf)) {
      if (!walk_specular(&c.w, f, &v)) return 0.0f;
      vcm_scattered(s, &v.surf, 0.0f, h->ns, eye, c.w.dir, true, vm, vc, &c.dvcm, &c.dvc, &c.dvm);
      if (!walk_on(&c.w, f, &v)) return 0.0f;
      continue;
    }
#endif
    float share = vcm_gloss_share(&v.surf);
    if (vcm_connectible(&v.surf) && !KASHA_VCM_EMISSION_ONLY) {
#if KASHA_VCM_CONNECT
      if (own) {
        if (VCM_LENGTH_COUNTS(c.w.depth + 2)) vcm_next_event(&c, s, f, &v, share, vm, rows);
        vcm_connect(&c, s, f, &v, share, vm, paths, store, path_last[pixel % (int)paths],
                    hash_combine(hash_combine(seed, (uint)pixel), (uint)c.w.depth), out, rows);
      }
#if KASHA_VCM_MERGE
      vcm_merge(&c, s, f, &v, share, vc, radius, KASHA_INV_PI / (radius * radius * s->bin_nm), store, sorted,
                cell_count, cell_end, inv_cell, mask, rows);
#endif
#else
      /* ppm: the first vertex with a non-delta part merges all of it, unless a mirror lobe
       * chosen by its probability carries the path on. */
      float p_mirror = v.surf.mirror ? v.probs.x : 0.0f;
      if (!(v.u_choice.x < p_mirror)) {
        vcm_merge(&c, s, f, &v, share, vc, radius,
                  KASHA_INV_PI / (radius * radius * s->bin_nm) / (1.0f - p_mirror), store, sorted, cell_count,
                  cell_end, inv_cell, mask, rows);
        return 0.0f;
      }
#endif
    }
    float3 probs = v.probs;
    float choice = v.u_choice.x;
    if (choice < probs.x) {
      if (!walk_gloss(&c.w, s, &v, sampler)) return 0.0f;
    } else if (choice < probs.x + probs.y || probs.z <= 0.0f) {
      lambert_bounce(&c.w, &v, probs.y);
      pw_scatter_diagonal(&c.w.p, v.surf.rho, 1.0f / probs.y);
#if KASHA_FLUORESCENCE
    } else {
      lambert_bounce(&c.w, &v, probs.z);
      pw_scatter_fluorescent(&c.w.p, f, v.surf.ehat, v.surf.a, 1.0f / probs.z);
#endif
    }
    if (!vcm_scattered(s, &v.surf, share, h->ns, eye, c.w.dir, c.w.specular, vm, vc, &c.dvcm, &c.dvc, &c.dvm))
      return 0.0f;
    if (!walk_on(&c.w, f, &v)) return 0.0f;
  }
  return walk_cut(&c.w, f);
}

/* One camera path per pixel (its light subpath: the pixel's index modulo `paths`), its estimate with the store's
 * chunk of light subpaths [chunk_first, chunk_end) added to the pixel's sums: the same path
 * (the same random numbers) with every chunk. `path_spectra`: KASHA_BINS floats per work item
 * for a light vertex's f·Φ. */
__kernel void vcm_camera_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, int paths, int chunk_first, int chunk_end,
                              float eta, float radius,
                              __global const float* store, __global const int* path_last,
                              __global const int* sorted, __global const int* cell_count,
                              __global const int* cell_end, float inv_cell, uint mask, __global float* path_spectra,
                              __global float* sums, __global int* rejected, __global float* cut, uint seed,
                              uint pass, int item_end) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  int pixel = launch_pixel(&camera, item_end);
  if (pixel < 0) return;
  /* The pixel's stream: a seed apart from the light subpaths'. */
  Sampler sampler = sampler_start(seed ^ 0x5bd1e995u, (uint)pixel, 0, pass, (uint)pixel);
  sampler_next_sample(&sampler, pass);
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  __global float* out = path_spectra + (long)(get_global_id(0) - get_global_offset(0)) * KASHA_BINS;
  int partner = pixel % paths; /* its light subpath */
  bool own = partner >= chunk_first && partner < chunk_end;
  float guard = vcm_camera_path(&s, &f, pixel, &sampler, (float)paths, eta, radius, store, path_last, sorted,
                                cell_count, cell_end, inv_cell, mask, own,
                                hash_combine(seed ^ 0x2545f491u, pass), out, rows);
  if (own) cut[pixel] = guard;
  if (film_rows_finite(rows))
    film_add(sums, pixel, rows);
  else
    rejected[pixel] += 1;
  add_ray_counts(&s, ray_counts);
}
