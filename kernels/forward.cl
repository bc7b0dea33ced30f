/* Forward Monte Carlo ray tracing (DESIGN §2.1) as light tracing: photons leave the lights, branch
 * at each hit with constant energy (photon_transport.h), and every hit with a Lambert part is
 * connected to the pinhole camera and splatted to the film (film_splat.h). Each photon draws its
 * random numbers from a stream of its own index, so the image does not depend on how photons are
 * spread over work items. A tabulated gloss lobe is splatted too; ideal mirrors seen by the camera
 * are out of reach of light tracing: a delta lobe never reflects a photon into a pinhole. */
#include "bvh_traversal.h"
#include "film_splat.h"
#include "hit_point.h"
#include "photon_transport.h"
#include "scene_params.h"

#define FORWARD_MAX_DEPTH 1000 /* a guard: absorption ends photons long before */

typedef struct {
  KCamera camera;
  const __global KBvhNode* nodes;
  const __global KTriangle* tris;
  const __global float* cmf;
  __global long* film;
  float film_scale;
  float ray_eps;
  int overflow;
} SplatTarget;

/* Adds radiance leaving x towards the camera (per nm, already times cos at x) to the film. */
inline void splat_to_camera(SplatTarget* t, float3 x, float3 ns, const float* radiance, float extra) {
  float importance;
  int pixel = camera_pixel(&t->camera, x, &importance);
  if (pixel < 0) return;
  float3 to_camera = camera_position(&t->camera) - x;
  float dist = length(to_camera);
  float3 dir = to_camera / dist;
  float cos_x = dot(ns, dir);
  if (cos_x <= 0.0f) return;
  if (bvh_occluded(t->nodes, t->tris, x + ns * t->ray_eps, dir, 0.0f, dist - t->ray_eps)) return;
  float k = cos_x * importance * extra;
  __global long* cell = t->film + (long)pixel * KASHA_FILM_ROWS;
#if KASHA_SPECTRAL_FILM
  for (int i = 0; i < KASHA_BINS; ++i)
    if (radiance[i] != 0.0f) splat_fixed(cell + i, radiance[i] * k, t->film_scale, &t->overflow);
#else
  for (int r = 0; r < 3; ++r) {
    float s = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) s += t->cmf[r * KASHA_BINS + i] * radiance[i];
    if (s != 0.0f) splat_fixed(cell + r, s * k, t->film_scale, &t->overflow);
  }
#endif
}

__kernel void trace_forward(KCamera camera, KASHA_SCENE_PARAMS, __global const float* cmf,
                            float bin_nm, float ray_eps, int photons, int photons_per_item, int max_depth,
                            __global long* film, float film_scale,
                            __global float* stats, /* per item: emitted, absorbed, escaped, in flight (W) */
                            __global int* overflow, uint seed, uint pass) {
  int item = get_global_id(0);
  int first = item * photons_per_item, last = min(first + photons_per_item, photons);
  if (first >= last) return;
  SplatTarget target = {camera, nodes, tris, cmf, film, film_scale, ray_eps, 0};
  float emitted = 0.0f, absorbed = 0.0f, escaped = 0.0f, in_flight = 0.0f;
  for (int index = first; index < last; ++index) {
    Rng rng = rng_seed(seed, pass, (uint)index);
    LightOrigin o;
    Photon p = emit_photon(tris, light_tri, light_cdf, light_count, emitter_radiance, emitter_area_pdf, bin_nm,
                           (float)photons, &rng, &o);
    emitted += photon_total(&p);
    /* The light point seen directly: Le cos / (p_area · photons). */
    float le[KASHA_BINS];
    for (int i = 0; i < KASHA_BINS; ++i) le[i] = emitter_radiance[o.emitter * KASHA_BINS + i];
    splat_to_camera(&target, p.position, o.normal, le, 1.0f / (o.area_pdf * (float)photons));
    p.position += o.normal * ray_eps;

    bool alive = true;
    for (int depth = 0; depth < max_depth && alive; ++depth) {
      HitPoint h;
      if (!intersect_scene(nodes, tris, p.position, p.direction, &h)) {
        escaped += photon_total(&p);
        alive = false;
        break;
      }
      float3 ns = h.ns, x = h.x;
      const __global KMaterial* m = &materials[h.material];
      Surface s;
      load_surface(m, spectra, &s);
      if (surface_has_lambert(&s)) {
        /* Radiance per nm leaving x per unit flux: (ρ_i Φ_i + ê_i (a·Φ)) / (π Δλ). */
        float out[KASHA_BINS];
        for (int i = 0; i < KASHA_BINS; ++i) out[i] = s.rho[i] * p.power[i];
#if KASHA_FLUORESCENCE
        if (s.fluorescent) {
          float absorbed_for_fluorescence = 0.0f;
          for (int i = 0; i < KASHA_BINS; ++i) absorbed_for_fluorescence += s.a[i] * p.power[i];
          for (int i = 0; i < KASHA_BINS; ++i) out[i] += s.ehat[i] * absorbed_for_fluorescence;
        }
#endif
        splat_to_camera(&target, x, ns, out, KASHA_INV_PI / bin_nm);
      }
#if KASHA_GLOSS
      if (s.g > 0.0f && !s.mirror) {
        /* A tabulated lobe can be evaluated towards the camera: white, f_g Φ / Δλ. */
        float3 to_camera = normalize(camera_position(&camera) - x);
        float f = s.g * lobe_brdf(m, lobes, to_camera, -p.direction, ns);
        if (f > 0.0f) splat_to_camera(&target, x, ns, p.power, f / bin_nm);
      }
#endif
      float before = photon_total(&p);
      if (scatter_photon(&p, &s, m, lobes, x, ns, ray_eps, &rng) == BRANCH_ABSORBED) {
        absorbed += before;
        alive = false;
      }
    }
    if (alive) in_flight += photon_total(&p);
  }
  stats[4 * item + 0] = emitted;
  stats[4 * item + 1] = absorbed;
  stats[4 * item + 2] = escaped;
  stats[4 * item + 3] = in_flight;
  if (target.overflow) atomic_add(overflow, target.overflow);
}
