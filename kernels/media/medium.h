/* Participating media (docs/media.md): media between surfaces, bounded by shapes' medium
 * interfaces (KTriMedia), homogeneous or scaled by a grid of density (density_grid.h). A path
 * carries the medium it travels in; crossing a boundary (a refraction, or an "interface" shape,
 * which has no surface and is passed straight through) puts it in the medium on the far side.
 * Along a segment the light is attenuated by exp(−σt(λ) ℓ) per bin, ℓ the segment's optical
 * length in the medium (its length where homogeneous, ∫ density in a grid). Compiled in only for
 * scenes with media (KASHA_MEDIA). */
#ifndef KASHA_MEDIUM_H
#define KASHA_MEDIUM_H

#include "geometry/hit_point.h"
#include "geometry/scene_view.h"
#include "materials/hit_material.h"

#ifndef KASHA_MEDIA
#define KASHA_MEDIA 0
#endif
/* Media that scatter or fluoresce: free flights and collisions (transport/medium_flight.h). */
#ifndef KASHA_SCATTERING
#define KASHA_SCATTERING 0
#endif
#ifndef KASHA_MEDIA_COUNT
#define KASHA_MEDIA_COUNT 1
#endif
#ifndef KASHA_SCRATCH_MEDIA
#define KASHA_SCRATCH_MEDIA 0
#endif
/* The most interfaces a ray passes through on its way to a surface: a guard against a ray stuck
 * on a degenerate boundary, far beyond what a scene's nested media make. */
#define KASHA_MAX_INTERFACES 64

#include "media/colour_grid.h"
#include "media/density_grid.h"

#if KASHA_MEDIA
/* How far a ray has travelled in each medium since its last vertex, as optical length (a grid's
 * ∫ density): a medium's transmittance depends only on that, so the order of the pieces does not
 * matter. */
typedef struct {
  float d[KASHA_TRAIL_SLOTS]; /* one per medium, and a component grid's further components' */
} MediaTrail;

inline void trail_clear(MediaTrail* t) {
  for (int m = 0; m < KASHA_TRAIL_SLOTS; ++m) t->d[m] = 0.0f;
}

inline void trail_add(MediaTrail* t, int medium, float d) {
  if (medium >= 0) t->d[medium] += d;
}

#if KASHA_GRID_COMPONENTS
/* A component grid's integrals ∫ ρ_k (components_march) onto the trail. */
inline void trail_add_components(MediaTrail* t, const __global KMedium* md, int medium,
                                 const float* sums) {
  for (int k = 0; k < md->components; ++k) t->d[component_slot(md, medium, k)] += sums[k];
}
#endif

/* The optical length of org + t dir, t in [0, len], in medium m (≥ 0): len where it is
 * homogeneous. */
inline float medium_optical_length(const SceneView* s, int m, float3 org, float3 dir, float len) {
#if KASHA_MEDIUM_GRIDS
  const __global KMedium* md = &s->media[m];
  float unused;
  if (md->density >= 0) return grid_march(s, md, org, dir, len, -1.0f, &unused);
#endif
  return len;
}

/* 1 / the density at x in medium m ≥ 0 (1 where homogeneous, 0 where the density is): a merge
 * at a collision divides by it, as the stored collisions around x are denser by it (each record
 * divided by its own density instead failed the gridded furnace: photons in thin smoke then
 * weigh up to 1/ρ). */
inline float medium_inverse_density(const SceneView* s, int m, float3 x) {
#if KASHA_MEDIUM_GRIDS
  const __global KMedium* md = &s->media[m];
#if KASHA_GRID_COMPONENTS
  if (md->components > 0) return 1.0f; /* its flights weigh with the true coefficients */
#endif
  if (md->density >= 0) {
    float d = grid_density_at(s, md, grid_map(md, x, 1.0f));
    return d > 0.0f ? 1.0f / d : 0.0f;
  }
#endif
  return 1.0f;
}

/* The segment org + t dir, t in [0, len], in `medium` (-1: vacuum), onto the trail. */
inline void trail_add_span(const SceneView* s, MediaTrail* t, int medium, float3 org, float3 dir, float len) {
  if (medium < 0) return;
#if KASHA_GRID_COMPONENTS
  const __global KMedium* md = &s->media[medium];
  if (md->components > 0) {
    float sums[KASHA_GRID_COMPONENTS], unused;
    for (int k = 0; k < md->components; ++k) sums[k] = 0.0f;
    components_march(s, md, org, dir, len, 0, -1.0f, sums, &unused);
    trail_add_components(t, md, medium, sums);
    return;
  }
#endif
  t->d[medium] += medium_optical_length(s, medium, org, dir, len);
}

inline bool trail_empty(const MediaTrail* t) {
  for (int m = 0; m < KASHA_TRAIL_SLOTS; ++m)
    if (t->d[m] > 0.0f) return false;
  return true;
}

/* Bin i's transmittance along the trail: exp(−Σ_m σt_m,i d_m). A medium that does not absorb in
 * bin i lets an infinite ray through there (0 · ∞ is not taken). */
inline float trail_transmittance(const SceneView* s, const MediaTrail* t, int i) {
  float tau = 0.0f;
  for (int m = 0; m < KASHA_MEDIA_COUNT; ++m) {
#if KASHA_GRID_COMPONENTS
    const __global KMedium* md = &s->media[m];
    if (md->components > 0) {
      for (int k = 0; k < md->components; ++k) {
        float d = t->d[component_slot(md, m, k)],
              sigma = s->spectra[md->sigma_t + k * KASHA_BINS + i];
        if (d > 0.0f && sigma > 0.0f) tau += sigma * d;
      }
      continue;
    }
#endif
    if (!(t->d[m] > 0.0f)) continue;
    float sigma = s->spectra[s->media[m].sigma_t + i];
    if (sigma > 0.0f) tau += sigma * t->d[m];
  }
  return exp(-tau);
}

/* tr[i] = bin i's transmittance along the trail, every bin; returns their mean, T̄. */
inline float trail_bins(const SceneView* s, const MediaTrail* t, float* tr) {
  float sum = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) sum += tr[i] = trail_transmittance(s, t, i);
  return sum / KASHA_BINS;
}

/* The medium a ray leaving the hit along dir travels in: across a boundary the medium on dir's
 * side (outside where dir leaves by the front), and otherwise the one it was in, `medium` —
 * pbrt-v4's rule, so a shape inside a medium without an interface of its own stays in it. */
inline int medium_after(const SceneView* s, int tri, float3 front, float3 dir, int medium) {
#if KASHA_MEDIUM_BOUNDARIES
  KTriMedia tm = s->tri_media[tri];
  if (tm.inside != tm.outside) return dot(dir, front) > 0.0f ? tm.outside : tm.inside;
#endif
  return medium;
}

/* Whether the hit's triangle is an interface, which rays pass through. */
inline bool hit_interface(const SceneView* s, const HitPoint* h) {
  return h->material >= 0 && s->materials[h->material].kind == KASHA_KIND_INTERFACE;
}

/* Through the interface h along dir: *medium becomes the far side's, and the ray goes on from just
 * past the surface (the returned origin). One rule for every walk through interfaces. */
inline float3 cross_interface(const SceneView* s, const HitPoint* h, float3 dir, int* medium) {
  *medium = medium_after(s, h->tri, h->n, dir, *medium);
  return h->x + (dot(dir, h->n) > 0.0f ? h->n : -h->n) * h->eps;
}

/* The closest surface along the ray (intersect_surface) that is not an interface: the ray passes
 * through interfaces, *medium following it, and each medium's length goes on the trail; h->t is
 * the whole distance. False: the ray leaves the scene (an infinite length in its last medium). */
inline bool intersect_through(const SceneView* s, float3 org, float3 dir, int* medium, MediaTrail* trail,
                              HitPoint* h) {
  float travelled = 0.0f;
  for (int k = 0; k < KASHA_MAX_INTERFACES; ++k) {
    if (!intersect_surface(s, org, dir, h)) {
      trail_add_span(s, trail, *medium, org, dir, INFINITY);
      return false;
    }
    trail_add_span(s, trail, *medium, org, dir, h->t);
    travelled += h->t;
    if (!hit_interface(s, h)) {
      h->t = travelled;
      return true;
    }
    org = cross_interface(s, h, dir, medium);
  }
  return false;
}

/* Whether the segment from x (offset eps off its surface along ns) to dist along wi, short of the
 * far end's offset far_eps (as segment_occluded), is free of surfaces other than interfaces; the
 * segment starts in `medium`. *tr: its transmittance per bin in the work item's scratch, or null
 * where it crosses no medium (1 in every bin). */
inline bool segment_clear(const SceneView* s, float3 x, float3 ns, float eps, float3 wi, float dist, float far_eps,
                          int medium, const __global float** tr) {
  *tr = 0;
  MediaTrail trail;
  trail_clear(&trail);
  float reach = dist * (1.0f - 1e-4f) - eps - far_eps, covered = 0.0f;
  float3 org = x + ns * eps;
  for (int k = 0; reach > 0.0f; ++k) {
    if (k == KASHA_MAX_INTERFACES) return false;
    ++s->rays->shadow;
    HitPoint h;
    if (!intersect_scene_within(s, org, wi, reach, &h)) break;
    if (!hit_interface(s, &h)) return false;
    trail_add_span(s, &trail, medium, org, wi, h.t);
    covered += h.t;
    reach -= h.t;
    org = cross_interface(s, &h, wi, &medium);
  }
  trail_add_span(s, &trail, medium, org, wi, fmax(dist - covered, 0.0f));
  if (trail_empty(&trail)) return true;
  __global float* out = s->scratch + KASHA_SCRATCH_MEDIA;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = trail_transmittance(s, &trail, i);
  *tr = out;
  return true;
}

/* The light `le` (global, N values) as it arrives over the segment of segment_clear: le itself,
 * or its product with the segment's transmittance in the scratch; null where a surface blocks
 * the segment. */
inline const __global float* segment_light(const SceneView* s, float3 x, float3 ns, float eps, float3 wi, float dist,
                                           float far_eps, int medium, const __global float* le) {
  const __global float* tr;
  if (!segment_clear(s, x, ns, eps, wi, dist, far_eps, medium, &tr)) return 0;
  if (!tr) return le;
  __global float* out = s->scratch + KASHA_SCRATCH_MEDIA;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] *= le[i];
  return out;
}

/* The branch of a collision that `target` falls in, the branches' weights w laid end to end
 * (elastic first, then each of the medium's `fluorophores` dyes; target in [0, Σw)): 0 elastic,
 * 1 + k dye k. One walk for camera paths, photons and photon mapping's visible points. */
inline int medium_branch(const float* w, int fluorophores, float target) {
  int branch = 0;
#if KASHA_FLUORESCENCE
  for (float below = w[0]; branch < fluorophores && target >= below; below += w[branch]) ++branch;
#endif
  return branch;
}

/* The medium a light path leaves a light in: a light that is not a triangle its own, an emitting
 * triangle its shape's outside (lights emit from the front). In a scene where no shape bounds a
 * medium no ray ever changes medium, so all are in the camera's, the lights' paths too (whatever a
 * light's own says: camera paths, which meet them, cannot see it). */
inline int light_medium(const SceneView* s, int tri, const __global KLight* source) {
#if KASHA_MEDIUM_BOUNDARIES
  if (source) return source->medium;
  return tri >= 0 ? s->tri_media[tri].outside : -1;
#else
  return s->camera_medium;
#endif
}
#endif

#endif
