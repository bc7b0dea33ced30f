/* Forward Monte Carlo ray tracing (docs/design.md#forward-transport) as light tracing: photons leave the lights, branch
 * at each hit with constant energy (photon_transport.h), and every hit with a Lambert part is
 * connected to the pinhole camera and splatted to the film (film_splat.h). Each photon draws its
 * random numbers from a stream of its own index, so the image does not depend on how photons are
 * spread over work items. A tabulated gloss lobe is splatted too; ideal mirrors, glass and metal
 * seen by the camera are out of reach of light tracing: a delta lobe never sends a photon into a
 * pinhole, so they show black (the render says so). Photons pass through them as anywhere. */
#include "shared/launch_records.h"
#include "film/camera_splat.h"
#include "film/film_view.h"
#include "geometry/hit_point.h"
#include "materials/hit_material.h"
#include "transport/photon_medium.h"
#include "transport/photon_transport.h"
#include "geometry/scene_view.h"

#if KASHA_ROUGH
/* A photon at a rough interface, connected to the camera on whichever side it is: f(camera,
 * photon) Φ / Δλ, f evaluated as for radiance towards the camera (rough_interface.h). A
 * dispersive dielectric is evaluated bin by bin, at each bin's index. */
inline void splat_rough(const SceneView* s, const FilmView* f, SplatTarget* t, const Surface* surf,
                        const HitPoint* h, const Photon* p, float* rows) {
  float3 x = h->x, n = hit_front(h);
  float3 to_camera = normalize(camera_point(&s->camera, x) - x);
  int pixel;
  float k;
  const __global float* tr;
  int medium = photon_medium_towards(s, p, h, to_camera);
#if KASHA_SHADING_NORMALS
  /* The camera on the geometric side the shading normal puts it on (no leak), the connection off
   * the geometric surface, and the arrival half of the adjoint correction (photon_transport.h). */
  if ((dot(to_camera, n) > 0.0f) != (dot(to_camera, h->n) > 0.0f)) return;
  if (!camera_connection(s, x, dot(to_camera, h->n) >= 0.0f ? h->n : -h->n, h->eps, medium, &pixel, &k, &tr)) return;
  k *= photon_arrival_correction(h, p->direction);
#else
  if (!camera_connection(s, x, dot(to_camera, n) >= 0.0f ? n : -n, h->eps, medium, &pixel, &k, &tr)) return;
#endif
  Frame fr = surface_frame(surf, n);
  float3 wo = to_local(&fr, to_camera), wi = to_local(&fr, -p->direction);
  float pdf, cos_m = 0.0f;
  film_rows_clear(rows);
  float scale = k / s->bin_nm;
#if KASHA_CONDUCTOR
  if (surf->kind == KASHA_KIND_CONDUCTOR) {
    float fv = conductor_lobe_eval(surf, wo, wi, &pdf, &cos_m);
    if (!(fv > 0.0f)) return;
    film_rows_conductor(f, p->power, tr, surf->eta_c, surf->k_c, surf->coat_c, cos_m, fv * scale, rows);
    splat_rows(t, pixel, rows);
    return;
  }
#endif
#if KASHA_DIELECTRIC
#if KASHA_DISPERSION
  if (surf->dispersive) {
    for (int i = 0; i < KASHA_BINS; ++i) {
      if (p->power[i] == 0.0f) continue;
      float v = p->power[i] * (tr ? tr[i] : 1.0f) * scale * rough_dielectric_eval(wo, wi, surf->eta_bins[i], surf->alpha, true, &pdf);
#if KASHA_SPECTRAL_FILM
      rows[i] += v;
#else
      for (int r = 0; r < 3; ++r) rows[r] += f->cmf[r * KASHA_BINS + i] * v;
#endif
    }
    splat_rows(t, pixel, rows);
    return;
  }
#endif
  float fv = rough_dielectric_eval(wo, wi, surf->eta, surf->alpha, true, &pdf);
  if (!(fv > 0.0f)) return;
  film_rows(f, p->power, tr, 0, fv * scale, rows);
  splat_rows(t, pixel, rows);
#endif
}
#endif

/* The light a photon p brings to a surface it hit, seen by the camera (light tracing): its Lambert
 * parts, a tabulated lobe and a rough coat's lobe towards the camera, splatted to the pixel. */
inline void splat_surface(const SceneView* s, const FilmView* f, SplatTarget* target, const Surface* surf,
                          const HitPoint* h, const Photon* p, float* rows) {
  int pixel;
  float k;
  const __global float* tr;
  float3 ns = hit_ng(h), x = h->x;
  const __global float* rho = surf->rho;
  bool through = false;
#if KASHA_TRANSMISSION
  /* A camera behind a transmitting surface sees the photon through its τ (surface.h). */
  if (surf->share_t > 0.0f && dot(camera_point(&s->camera, x) - x, ns) < 0.0f) {
    through = true;
    ns = -ns;
    rho = surf->tau;
  }
#endif
#if KASHA_GLOSS
  bool glossy = surf->g > 0.0f && !surf->mirror;
#else
  bool glossy = false;
#endif
#if KASHA_COATED
  bool coat_lobe = surface_coat_lobe(surf);
  glossy = glossy && !coat_lobe;
#else
  const bool coat_lobe = false;
#endif
  int medium = photon_medium_towards(s, p, h, camera_point(&s->camera, x) - x);
  if ((surface_has_lambert(surf) || glossy || coat_lobe) && camera_connection(s, x, ns, h->eps, medium, &pixel, &k, &tr)) {
    /* Radiance per nm leaving x per unit flux: (ρ_i Φ_i + ê_i (a·Φ)) / (π Δλ). */
    film_rows_clear(rows);
#if KASHA_SHADING_NORMALS
    /* Towards a camera below the shading normal's hemisphere the surface sends nothing. */
    if (hit_seen(h, normalize(x - camera_point(&s->camera, x))) == through) k = 0.0f;
    k *= photon_arrival_correction(h, p->direction);
#endif
    float lambert = k * KASHA_INV_PI / s->bin_nm;
#if KASHA_COATED
    /* Under a coat, t(θi) t(θo) / η² (coat.h). */
    if (surf->coated) lambert *= surface_lambert_weight(surf, dot(normalize(camera_point(&s->camera, x) - x), h->ns));
#endif
    film_rows(f, p->power, rho, tr, lambert, rows);
#if KASHA_FLUORESCENCE
    if (surf->fluorescent) film_rows(f, 0, surf->ehat, tr, spectrum_dot(KASHA_BINS, p->power, surf->a, 0) * lambert, rows);
#endif
#if KASHA_GLOSS
    if (glossy) {
      /* A tabulated lobe can be evaluated towards the camera: white, f_g Φ / Δλ. */
      float3 to_camera = normalize(camera_point(&s->camera, x) - x);
      float fg = surf->g * lobe_brdf(surf->m, s->lobes, to_camera, -p->direction, h->ns);
      if (fg > 0.0f) film_rows(f, p->power, tr, 0, fg * k / s->bin_nm, rows);
    }
#endif
#if KASHA_COATED
    if (coat_lobe) {
      /* A rough coat's GGX lobe towards the camera (coat.h), white: f Φ / Δλ. */
      Frame fr = frame_of(h->ns);
      float pdf;
      float fc = coat_lobe_eval(surf, to_local(&fr, normalize(camera_point(&s->camera, x) - x)),
                                to_local(&fr, -p->direction), &pdf);
      if (fc > 0.0f) film_rows(f, p->power, tr, 0, fc * k / s->bin_nm, rows);
    }
#endif
    splat_rows(target, pixel, rows);
  }
}

#if KASHA_SCATTERING
/* A photon's collision at x in its medium seen by the camera: the radiance per nm it sends there,
 * elastically Φ∘σs times the phase function, and through each dye ê Φ_d (a·Φ) / 4π, over Δλ. */
inline void splat_medium(const SceneView* s, const FilmView* f, SplatTarget* target, const Photon* p, float3 x,
                         float* rows) {
  int pixel;
  float k;
  const __global float* tr;
  if (!camera_connection_from_medium(s, x, p->medium, &pixel, &k, &tr)) return;
  const __global KMedium* m = &s->media[p->medium];
  float3 to_camera = normalize(camera_point(&s->camera, x) - x);
  float scale = k / s->bin_nm;
  film_rows_clear(rows);
  collision_film_rows(s, f, m, p, to_camera, tr, scale, rows);
  splat_rows(target, pixel, rows);
}
#endif

#if KASHA_MEDIUM_LIGHTS
/* A photon's start inside an emitting medium seen by the camera: the medium emits isotropically,
 * so the radiance per nm it sends there is Φ / (4π Δλ). */
inline void splat_emission_point(const SceneView* s, const FilmView* f, SplatTarget* target, const Photon* p,
                                 float* rows) {
  int pixel;
  float k;
  const __global float* tr;
  if (!camera_connection_from_medium(s, p->position, p->medium, &pixel, &k, &tr)) return;
  film_rows_clear(rows);
  film_rows(f, p->power, tr, 0, k * KASHA_INV_4PI / s->bin_nm, rows);
  splat_rows(target, pixel, rows);
}
#endif

/* A work item's energy ledger (W): emitted = absorbed + escaped + in flight, exactly. */
typedef struct {
  float emitted, absorbed, escaped, in_flight;
} Ledger;

/* The photon's next surface: through the media on the way, which attenuate it, and (with scattering
 * media) the collisions on the way, each seen by the camera and scattered (photon_medium.h), which
 * count as hits. False: the photon is gone (escaped, or ended at a collision); the ledger counts
 * what it lost. */
inline bool forward_next_surface(const SceneView* s, const FilmView* f, SplatTarget* target, Photon* p,
                                 Sampler* sampler, int* depth, int max_depth, float* rows, Ledger* l, HitPoint* h) {
  for (; *depth < max_depth; ++*depth) {
    float flying = photon_total(p);
#if KASHA_SCATTERING
    float tbar;
    int reached = photon_flight(p, s, sampler, *depth, h, &tbar);
#else
    int reached = photon_intersect(s, p, h) ? KASHA_FLIGHT_SURFACE : KASHA_FLIGHT_ESCAPED;
#endif
    l->absorbed += flying - photon_total(p); /* by the media on the way (none without them) */
    if (reached == KASHA_FLIGHT_ESCAPED) {
      l->escaped += photon_total(p);
      return false;
    }
    if (reached == KASHA_FLIGHT_SURFACE) return true;
#if KASHA_SCATTERING
    splat_medium(s, f, target, p, h->x, rows);
    float before = photon_total(p);
    if (scatter_photon_in_medium(p, s, h->x, sampler, *depth) == BRANCH_ABSORBED) {
      l->absorbed += before;
      return false;
    }
    l->absorbed += before - photon_total(p);
#endif
  }
  return false;
}

__kernel void trace_forward(KASHA_SCENE_PARAMS, KASHA_FILM_PARAMS, KForwardLaunch launch, __global ulong* film,
                            __global float* stats, /* per item: emitted, absorbed, escaped, in flight (W) */
                            __global int* overflow,
                            KASHA_LAUNCH_RANGE) {
  KASHA_SCENE_VIEW(s);
  KASHA_FILM_VIEW(f);
  const int photons = launch.photons, photons_per_item = launch.photons_per_item, max_depth = launch.max_depth;
  const int film_shift = launch.film_shift;
  const uint seed = launch.seed, pass = launch.pass;
  int item = launch_item(item_first);
  if (item >= item_end) return;
  int first = item * photons_per_item, last = min(first + photons_per_item, photons);
  if (first >= last) return;
  SplatTarget target = {film, film_shift, 0};
  Ledger l = {0.0f, 0.0f, 0.0f, 0.0f};
  float rows[KASHA_FILM_ROWS];
  for (int index = first; index < last; ++index) {
    Sampler sampler = photon_sampler(seed, pass, photons, index);
    LightOrigin o;
    Photon p = emit_photon(&s, (float)photons, true, &sampler, &o);
    l.emitted += photon_total(&p);
    if (origin_in_medium(&o) && !(p.start > 0.0f)) continue; /* drawn where the medium emits nothing */
#if KASHA_MEDIUM_LIGHTS
    /* A point of an emitting medium is a vertex (origin_depth): seen only under a cap above 0. */
    if (origin_in_medium(&o) && max_depth > 0) splat_emission_point(&s, &f, &target, &p, rows);
#endif
    /* The light point seen directly: Le cos / (p_area · photons). */
    int pixel;
    float k;
    const __global float* tr;
    if (!origin_in_medium(&o) && camera_connection(&s, p.position, o.normal, o.eps, photon_medium(&p), &pixel, &k, &tr)) {
      film_rows_clear(rows);
#if KASHA_EMISSION_TEXTURES
      k *= o.scale;
#endif
      film_rows(&f, 0, emitter_spectrum(&s, o.emitter), tr, k / (o.area_pdf * (float)photons), rows);
      splat_rows(&target, pixel, rows);
    }
    p.position += o.normal * o.eps;

    bool alive = true;
    for (int depth = origin_depth(&o); depth < max_depth && alive; ++depth) {
      HitPoint h;
      if (!forward_next_surface(&s, &f, &target, &p, &sampler, &depth, max_depth, rows, &l, &h)) {
        alive = depth == max_depth;
        break;
      }
#if KASHA_SHADING_NORMALS
      /* From below the shading normal's hemisphere: the surface does not scatter it (hit_seen). */
      if (!hit_seen(&h, p.direction)) {
        l.absorbed += photon_total(&p);
        alive = false;
        break;
      }
#endif
      Surface surf;
      load_surface_at(&s, &h, &surf);
#if KASHA_ROUGH
      if (surface_rough(&surf)) splat_rough(&s, &f, &target, &surf, &h, &p, rows);
#endif
      splat_surface(&s, &f, &target, &surf, &h, &p, rows);
      /* "Absorbed": the power a hit takes away, absorption and roulette (negative when roulette
       * scales a survivor up), so emitted = absorbed + escaped + in flight exactly. */
      float before = photon_total(&p);
      if (scatter_photon(&p, &surf, &s, &h, &sampler, depth) == BRANCH_ABSORBED) {
        l.absorbed += before;
        alive = false;
      } else {
        l.absorbed += before - photon_total(&p);
      }
    }
    if (alive) l.in_flight += photon_total(&p);
  }
  __global float* ledger = stats + 4 * (item - item_first); /* the launch's own items */
  ledger[0] = l.emitted;
  ledger[1] = l.absorbed;
  ledger[2] = l.escaped;
  ledger[3] = l.in_flight;
  if (target.overflow) atomic_add(overflow, target.overflow);
  add_ray_counts(&s, ray_counts);
}
