/* Bidirectional photon mapping (docs/design.md#photon-mapping), the two tracing passes; the grid, the gather and the
 * SPPM statistics are in photon_gather.cl, in the same program.
 * Photon pass: photons as in forward transport, stored at every hit with a Lambert part (before
 * they scatter) after their first bounce — direct light at the visible points is next-event
 * estimation's, so the photon map carries indirect light and caustics (as pbrt-v4's SPPM); gloss
 * bounces are followed, not stored. Camera pass: paths through gloss bounces to the first vertex
 * with a Lambert part, with backward's next-event estimation at each vertex (MIS only with the
 * gloss lobe: no path continues from the Lambert part) and emission hit along the way; the first
 * of a pixel's samples stores a visible point with the compact factor K (vertex_factor.h) there. */
#include "shared/launch_records.h"
#include "geometry/camera.h"
#include "transport/camera_walk.h"
#include "film/film_view.h"
#include "geometry/hit_point.h"
#include "materials/hit_material.h"
#include "shared/photon_layout.h"
#include "transport/photon_medium.h"
#include "transport/photon_transport.h"
#include "geometry/scene_view.h"
#include "shared/vertex_factor.h"

/* Where a launch's photons are stored: the store, its count (atomic) and capacity, and the stores a
 * segmented photon passes over before its own (launches of one photon only). */
typedef struct {
  __global float* store;
  __global int* stored;
  int capacity;
  int skip_left;
} StoreCursor;

/* The record a photon's next store goes to: null while a segmented photon passes over its first
 * stores, or past the store's capacity (counted, not written). */
inline __global float* next_record(StoreCursor* c) {
  if (c->skip_left > 0) {
    --c->skip_left;
    return 0;
  }
  int slot = atomic_inc(c->stored);
  return slot < c->capacity ? c->store + (long)slot * KASHA_PHOTON_FLOATS(KASHA_BINS, KASHA_SCATTERING) : 0;
}

/* A photon's record (photon_layout.h): where it is stored, the normal (0 in a medium), its key, its
 * power times `through`, and with scattering media its direction. */
inline void write_photon(__global float* rec, float3 x, float3 n, int index, int depth, const Photon* p,
                         float through) {
  rec[0] = x.x, rec[1] = x.y, rec[2] = x.z;
  rec[3] = n.x, rec[4] = n.y, rec[5] = n.z;
  rec[KASHA_PHOTON_INDEX] = as_float(index), rec[KASHA_PHOTON_DEPTH] = as_float(depth);
  if (through == 1.0f)
    for (int i = 0; i < KASHA_BINS; ++i) rec[KASHA_PHOTON_POWER + i] = p->power[i];
  else
    for (int i = 0; i < KASHA_BINS; ++i) rec[KASHA_PHOTON_POWER + i] = p->power[i] * through;
#if KASHA_SCATTERING
  __global float* d = rec + KASHA_PHOTON_DIRECTION(KASHA_BINS);
  d[0] = p->direction.x, d[1] = p->direction.y, d[2] = p->direction.z;
#endif
}

/* The photon's next surface hit h (photon_intersect); with scattering media, its collisions on
 * the way (photon_medium.h) count as hits: each after the first bounce is stored (normal 0), and
 * the photon scatters or re-emits there. False: it escaped or ended, or *depth reached `until`. */
inline bool photon_next_surface(const SceneView* s, Photon* p, Sampler* sampler, int* depth, int until, int index,
                                StoreCursor* cursor, HitPoint* h) {
#if KASHA_SCATTERING
  for (; *depth < until; ++*depth) {
    float tbar;
    int reached = photon_flight(p, s, sampler, *depth, h, &tbar);
    if (reached != KASHA_FLIGHT_SCATTERED) return reached == KASHA_FLIGHT_SURFACE;
    __global float* rec = *depth > 0 ? next_record(cursor) : 0;
    if (rec) write_photon(rec, h->x, (float3)(0.0f, 0.0f, 0.0f), index, *depth, p, 1.0f);
    if (scatter_photon_in_medium(p, s, h->x, sampler, *depth) == BRANCH_ABSORBED) return false;
  }
  return false;
#else
  return photon_intersect(s, p, h);
#endif
}

/* Photons [first_photon, first_photon + count) of the pass's `photons`, `photons_per_item` per work
 * item, stored from slot *stored on; a store past `capacity` is counted but not written, so the
 * host sees the overflow and traces the launch again into an emptier store. A photon that alone
 * stores more than the store holds is traced again in segments: `skip` of its stores are passed
 * over (launches of one photon only). */
__kernel void trace_photon_map(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, KPhotonTraceLaunch launch,
                               __global float* store, __global int* stored,
                               __global float* cut, /* per item: power the depth guard cut, per photon's start */
                               KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  const int photons = launch.photons, first_photon = launch.first_photon, count = launch.count;
  const int photons_per_item = launch.photons_per_item, skip = launch.skip, capacity = launch.capacity;
  const uint seed = launch.seed, pass = launch.pass;
  int item = launch_item(item_first);
  if (item >= item_end) return;
  int first = first_photon + item * photons_per_item;
  int last = min(first + photons_per_item, first_photon + count);
  float guard = 0.0f;
#ifdef KASHA_DEPTH_CAP
  /* A photon stored at hit k has k scattering vertices behind it and the visible point makes one
   * more: hits from the cap's on would count none (gather_photons checks the sum). */
  const int until = min(KASHA_MAX_PATH_DEPTH, KASHA_DEPTH_CAP);
#else
  const int until = KASHA_MAX_PATH_DEPTH;
#endif
  for (int index = first; index < last; ++index) {
    Sampler sampler = photon_sampler(seed, pass, photons, index);
    LightOrigin o;
    Photon p = emit_photon(&s, (float)photons, true, &sampler, &o);
    if (origin_in_medium(&o) && !(p.start > 0.0f)) continue; /* drawn where the medium emits nothing */
    p.position += o.normal * o.eps;
    StoreCursor cursor = {store, stored, capacity, skip};
    /* A photon from inside an emitting medium starts a vertex deep (origin_depth), so it is stored
     * from its first hit: no next-event estimate reaches a medium's light. */
    for (int depth = origin_depth(&o);; ++depth) {
      HitPoint h;
      bool hit = depth < until && photon_next_surface(&s, &p, &sampler, &depth, until, index, &cursor, &h);
      if (depth == KASHA_MAX_PATH_DEPTH) guard += photon_total(&p) / p.start;
      if (!hit) break;
      float3 ns = hit_ng(&h), x = h.x;
#if KASHA_SHADING_NORMALS
      /* From below the shading normal's hemisphere: the surface does not scatter it (hit_seen). */
      if (!hit_seen(&h, p.direction)) break;
#endif
      Surface surf;
      load_surface_at(&s, &h, &surf);
      __global float* rec = depth > 0 && surface_has_lambert(&surf) ? next_record(&cursor) : 0;
      if (rec) {
#if KASHA_COATED
        /* Under a coat, the power that reaches the base: t(θi) Φ (coat.h); the visible point's
         * factor holds the rest. */
        float through = surf.coated ? coat_transmission(&surf, h.cos_in) : 1.0f;
#else
        float through = 1.0f;
#endif
#if KASHA_SHADING_NORMALS
        through *= photon_arrival_correction(&h, p.direction);
#endif
        write_photon(rec, x, ns, index, depth, &p, through);
      }
      if (scatter_photon(&p, &surf, &s, &h, &sampler, depth) == BRANCH_ABSORBED) break;
    }
  }
  if (first < last) cut[item] = guard;
  add_ray_counts(&s, ray_counts);
}

#if KASHA_SCATTERING
/* A camera path's collision in a medium, where it ends: next-event estimation for the direct light
 * (not weighed: no path goes on from here to meet the light), and with `vp` the pixel's visible
 * point — the branch chosen as backward chooses it (medium_branches), its factor over the branch's
 * probability: elastic, w∘σs with ωo and the medium's g for the gather's phase function; a dye's,
 * C(w∘ê) Φ aᵀ, isotropic (g 0). No normal marks it as a medium's (volume_gather.h). */
inline void medium_visible_point(const CameraWalk* w, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                 __global float* vp, float travelled, float* rows) {
  const __global KMedium* m = &s->media[w->medium];
  float probs[1 + KASHA_MEDIUM_FLUOROPHORES], unweighed[1 + KASHA_MEDIUM_FLUOROPHORES];
  if (!medium_branches(w, s, f, m, probs)) return;
  for (int k = 0; k <= KASHA_MEDIUM_FLUOROPHORES; ++k) unweighed[k] = 0.0f;
  walk_medium_next_event(w, s, f, v, m, unweighed, rows);
  if (!vp) return;
  int branch = medium_branch(probs, m->fluorophores, v->u_choice.x);
  if (!(probs[branch] > 0.0f)) return;
  float3 x = v->h.x, wo = -w->dir;
  vp[0] = x.x, vp[1] = x.y, vp[2] = x.z;
  vp[3] = 0.0f, vp[4] = 0.0f, vp[5] = 0.0f;
#ifdef KASHA_DEPTH_CAP
  vp[KASHA_VP_VALID] = 1.0f + (float)w->depth;
#else
  vp[KASHA_VP_VALID] = 1.0f;
#endif
  vp[KASHA_VP_DISTANCE] = travelled;
  VertexFactorLayout layout = {KASHA_BINS, KASHA_FILM_ROWS, KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE, f->cmf};
  __global float* g = vp + KASHA_VP_WO(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE);
  g[0] = wo.x, g[1] = wo.y, g[2] = wo.z;
  vp[KASHA_VP_G(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE)] = branch == 0 ? m->g : 0.0f;
  /* In a grid the photons around x are denser by its density there (medium_inverse_density). */
  float sparse = medium_inverse_density(s, w->medium, x);
  if (branch == 0) {
    vf_build_medium(layout, vp, w->p.w, medium_scattering(s, m), 0, 0, sparse / probs[0]);
  }
#if KASHA_FLUORESCENCE
  else {
    const __global KFluorophore* fl = &m->fluorophore[branch - 1];
    vf_build_medium(layout, vp, w->p.w, 0, s->spectra + fl->emission, s->spectra + fl->absorption,
                    sparse * fl->yield / probs[branch]);
  }
#endif
}
#endif

/* One camera path of pixel `pixel` (camera_walk.h) through gloss bounces alone, so its weight
 * stays diagonal; adds emission and next-event estimates to rows. With `vp` (a pixel's first
 * sample) it stores the visible point where the path ends on a Lambert part. Returns what the
 * path still carried (relative to its start) if the depth guard cut it. */
inline float camera_path(const SceneView* s, const FilmView* f, int pixel, Sampler* sampler, __global float* vp,
                         float* rows) {
  CameraWalk w;
  float3 o, d = camera_ray(&s->camera, pixel, sampler, &o);
  walk_start(&w, s, f, o, d);
  float travelled = 0.0f;
  CameraVertex v;
  while (walk_vertex(&w, s, f, sampler, &v, rows)) {
    travelled += v.h.t;
#if KASHA_SCATTERING
    if (v.in_medium) {
      medium_visible_point(&w, s, f, &v, vp, travelled, rows);
      return 0.0f;
    }
#endif
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    /* Through glass and metal to the diffuse surface behind: caustics seen through them. */
    if (surface_specular(&v.surf)) {
      if (!walk_interface(&w, s, f, &v, sampler, rows)) return 0.0f;
      continue;
    }
#endif
    /* Gloss or the Lambert parts, by their energies under equal-energy light (as backward). */
    float p_gloss = v.probs.x;
    bool lambert = v.probs.y + v.probs.z > 0.0f;
    walk_next_event(&w, s, f, &v, lambert, (float3)(p_gloss, 0.0f, 0.0f), rows);
    if (lambert && v.u_choice.x >= p_gloss) {
      if (vp) {
        /* The visible point, K over 1 − P_gloss. */
        float3 x = v.h.x, ns = hit_ng(&v.h);
        vp[0] = x.x, vp[1] = x.y, vp[2] = x.z;
        vp[3] = ns.x, vp[4] = ns.y, vp[5] = ns.z;
#ifdef KASHA_DEPTH_CAP
        vp[KASHA_VP_VALID] = 1.0f + (float)w.depth; /* the gather's cap needs the camera's bounces */
#else
        vp[KASHA_VP_VALID] = 1.0f;
#endif
        vp[KASHA_VP_DISTANCE] = travelled;
        VertexFactorLayout layout = {KASHA_BINS, KASHA_FILM_ROWS, KASHA_SPECTRAL_FILM, KASHA_FLUORESCENCE, f->cmf};
        float k = KASHA_INV_PI / (1.0f - p_gloss);
        const __global float* rho = v.surf.rho;
#if KASHA_TRANSMISSION
        /* A transmitting surface gathers one side's photons, drawn by its share on the unused
         * direction sample: those arriving through it take τ (surface.h). */
        if (v.surf.share_t > 0.0f) {
          bool through = v.u_dir.x < v.surf.share_t;
          k /= surface_side_share(&v.surf, through);
          rho = surface_side_spectrum(&v.surf, through);
          if (through) ns = -ns;
          vp[3] = ns.x, vp[4] = ns.y, vp[5] = ns.z;
        }
#endif
#if KASHA_COATED
        /* Under a coat, t(θo) / η² towards the viewer; the photons carry their own t(θi). */
        if (v.surf.coated) k *= v.surf.lambert_out;
#endif
#if KASHA_FLUORESCENCE
        vf_build(layout, vp, w.p.w, rho, v.surf.ehat, v.surf.a, k);
#else
        vf_build(layout, vp, w.p.w, rho, 0, 0, k);
#endif
      }
      return 0.0f;
    }
    if (!walk_gloss(&w, s, &v, sampler) || !walk_on(&w, s, f, &v)) return 0.0f;
  }
  return walk_cut(&w, f);
}

/* `spp` camera samples per pixel: their mean emission and next-event estimate goes to `direct`
 * (summed over passes, compensated), the first one's Lambert vertex is the pixel's visible point
 * for this pass. A pixel's first visible point sets its gather radius: `radius0` (> 0: --radius,
 * kept at least 1/100 of the pixel's footprint) or one pixel's footprint there, within
 * `max_radius`; pixels where --radius was raised are counted in *raised. */
__kernel void camera_pass(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, __global float* visible_points,
                          __global float* direct,       /* pixels × KASHA_FILM_ROWS: Σ over passes of the mean */
                          __global float* direct_carry, /* the compensation of that sum (Kahan) */
                          __global int* rejected,       /* per pixel: samples that were not finite, this pass */
                          __global float* cut,          /* per pixel: weight the depth guard cut, this pass */
                          __global float* radius,       /* per pixel: the SPPM radius, 0 before a visible point */
                          __global int* raised, KPhotonCameraLaunch launch,
                          KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  const float radius0 = launch.radius0, footprint = launch.footprint, max_radius = launch.max_radius;
  const int spp = launch.spp;
  const uint seed = launch.seed, pass = launch.pass;
  int pixel = launch_pixel(&s.camera, item_first, item_end);
  if (pixel < 0) return;
  const int vp_floats = KASHA_VP_FLOATS(KASHA_BINS, KASHA_FILM_ROWS, KASHA_FLUORESCENCE, KASHA_SCATTERING);
  __global float* vp = visible_points + (long)pixel * vp_floats;
  vp[KASHA_VP_VALID] = 0.0f;
  float sum[KASHA_FILM_ROWS];
  film_rows_clear(sum);
  float guard = 0.0f;
  int bad = 0;
  /* The pixel's stream: a seed apart from the photons'. */
  Sampler sampler = sampler_start(seed ^ 0x5bd1e995u, (uint)pixel, 0, pass, (uint)pixel);
  for (int k = 0; k < spp; ++k) {
    sampler_next_sample(&sampler, pass * (uint)spp + (uint)k);
    float rows[KASHA_FILM_ROWS];
    film_rows_clear(rows);
    guard += camera_path(&s, &f, pixel, &sampler, k == 0 ? vp : 0, rows);
    if (!film_rows_finite(rows)) {
      ++bad;
      continue;
    }
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) sum[r] += rows[r];
  }
  __global float* acc = direct + (long)pixel * KASHA_FILM_ROWS;
  __global float* carry = direct_carry + (long)pixel * KASHA_FILM_ROWS;
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) {
    float y = sum[r] / (float)spp - carry[r], t = acc[r] + y;
    carry[r] = (t - acc[r]) - y;
    acc[r] = t;
  }
  rejected[pixel] = bad;
  cut[pixel] = guard;
  add_ray_counts(&s, ray_counts);
  if (radius[pixel] == 0.0f && vp[KASHA_VP_VALID] != 0.0f) {
    float own = footprint * vp[KASHA_VP_DISTANCE], r = own;
    if (radius0 > 0.0f) {
      r = radius0;
      if (radius0 < own / 100.0f) {
        r = own / 100.0f;
        atomic_inc(raised);
      }
    }
    r = min(r, max_radius);
    radius[pixel] = r > 0.0f ? r : max_radius;
  }
}

#include "photon/photon_gather.cl"
