/* Backward Monte Carlo ray tracing (DESIGN §2.2): camera paths whose colour is a diagonal spectrum
 * or, after a fluorescent bounce, a rank-1 factor (path_weight.h). At each vertex: emission,
 * next-event estimation to an emitting triangle (MIS with the branch that could have hit it),
 * then one branch — gloss, passive, fluorescent — chosen in proportion to the energy it would
 * bring to the film under equal-energy light; the rest is absorption (Russian roulette).
 * One work item renders one pixel's samples of a pass, so the film needs no atomics. */
#include "bvh_traversal.h"
#include "camera.h"
#include "gloss_lobe.h"
#include "hit_point.h"
#include "lights.h"
#include "path_weight.h"
#include "rng.h"
#include "sampling.h"
#include "scene_params.h"
#include "surface.h"

#define MAX_DEPTH 1000 /* a guard: Russian roulette ends paths long before */

typedef struct {
  const __global KBvhNode* nodes;
  const __global KTriangle* tris;
  const __global KMaterial* materials;
  const __global float* spectra;
  const __global float* lobes;
  const __global float* emitter_radiance;
  const __global float* emitter_area_pdf;
  const __global int* light_tri;
  const __global float* light_cdf;
  int light_count;
  const __global float* cmf;
  const __global float* importance;
  float ray_eps;
} SceneView;

inline void load_radiance(const SceneView* s, int emitter, float* le) {
  for (int i = 0; i < KASHA_BINS; ++i) le[i] = s->emitter_radiance[emitter * KASHA_BINS + i];
}

/* Branch probabilities at a vertex: P_g, P_p, P_f; 1 − their sum is absorption. */
inline float3 branch_probabilities(const PathWeight* p, const SceneView* s, const Surface* surf) {
  float w0 = pw_energy(p, s->importance, 0);
  if (!(w0 > 0.0f)) return (float3)(0.0f);
  float wg = surf->g * w0;
  float wp = surf->passive ? pw_energy(p, s->importance, surf->rho) : 0.0f;
  float wf = 0.0f;
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) wf = pw_energy(p, s->importance, surf->ehat) * surf->a_sum;
#endif
  float total = fmax(w0, wg + wp + wf);
  return (float3)(wg, wp, wf) / total;
}

/* Next-event estimation at x (shading normal ns on the viewer's side, wo towards the viewer). */
inline void next_event(const PathWeight* p, const SceneView* s, const Surface* surf,
                       const __global KMaterial* m, float3 x, float3 ns, float3 wo, float3 probs, Rng* rng,
                       float* rows) {
  LightPoint lp = sample_light(s->tris, s->light_tri, s->light_cdf, s->light_count, rng_next_float(rng),
                               rng_next_float(rng), rng_next_float(rng));
  float3 to = lp.position - x;
  float dist = length(to);
  if (!(dist > 2.0f * s->ray_eps)) return;
  float3 wi = to / dist;
  float cos_x = dot(ns, wi), cos_l = -dot(lp.normal, wi);
  if (cos_x <= 0.0f || cos_l <= 0.0f) return;
  if (bvh_occluded(s->nodes, s->tris, x + ns * s->ray_eps, wi, 0.0f, dist - 2.0f * s->ray_eps)) return;
  float pdf_light = light_pdf_solid_angle(s->emitter_area_pdf, lp.emitter, dist, cos_l);
  float le[KASHA_BINS];
  load_radiance(s, lp.emitter, le);
  float lambert_pdf = cosine_hemisphere_pdf(cos_x);
  float base = cos_x / pdf_light;
  if (surf->passive) {
    float v[KASHA_BINS];
    for (int i = 0; i < KASHA_BINS; ++i) v[i] = surf->rho[i] * le[i];
    pw_add(p, s->cmf, v, base * KASHA_INV_PI * mis_weight(pdf_light, probs.y * lambert_pdf), rows);
  }
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) {
    float absorbed = 0.0f;
    for (int i = 0; i < KASHA_BINS; ++i) absorbed += surf->a[i] * le[i];
    pw_add(p, s->cmf, surf->ehat, absorbed * base * KASHA_INV_PI * mis_weight(pdf_light, probs.z * lambert_pdf),
           rows);
  }
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) {
    float f = lobe_brdf(m, s->lobes, wo, wi, ns);
    if (f > 0.0f) {
      float lobe = lobe_pdf(m, s->lobes, dot(wi, reflect_dir(-wo, ns)));
      pw_add(p, s->cmf, le, surf->g * f * base * mis_weight(pdf_light, probs.x * lobe), rows);
    }
  }
#endif
}

/* One camera path; adds its estimate to rows. */
inline void trace_camera_path(const SceneView* s, float3 org, float3 dir, Rng* rng, float* rows) {
  PathWeight p;
  pw_init(&p, s->cmf);
  bool specular = true; /* the camera ray, or a mirror bounce: emission is not also sampled by NEE */
  float prev_pdf = 0.0f;
  for (int depth = 0; depth < MAX_DEPTH; ++depth) {
    HitPoint h;
    if (!intersect_scene(s->nodes, s->tris, org, dir, &h)) return;
    float3 wo = -dir, ns = h.ns, x = h.x;

    if (h.emitter >= 0 && h.front) {
      float weight = 1.0f;
      if (!specular)
        weight = mis_weight(prev_pdf, light_pdf_solid_angle(s->emitter_area_pdf, h.emitter, h.t, dot(h.n, wo)));
      float le[KASHA_BINS];
      load_radiance(s, h.emitter, le);
      pw_add(&p, s->cmf, le, weight, rows);
    }

    const __global KMaterial* m = &s->materials[h.material];
    Surface surf;
    load_surface(m, s->spectra, &surf);
    float3 probs = branch_probabilities(&p, s, &surf);
    if (probs.x + probs.y + probs.z <= 0.0f) return;
    if (s->light_count > 0 && (surface_has_lambert(&surf) || (surf.g > 0.0f && !surf.mirror)))
      next_event(&p, s, &surf, m, x, ns, wo, probs, rng, rows);

    float choice = rng_next_float(rng);
    float u1 = rng_next_float(rng), u2 = rng_next_float(rng);
    if (choice < probs.x) {
      /* Gloss: white, weight g (times the lobe's cosine ratio), below the horizon absorbed. */
      float3 mirror = reflect_dir(dir, ns);
      if (surf.mirror) {
        dir = mirror;
        specular = true;
        pw_scatter_diagonal(&p, 0, surf.g / probs.x);
      } else {
        float pdf;
        float3 wi = sample_lobe(m, s->lobes, mirror, u1, u2, rng_next_float(rng), &pdf);
        float ci = dot(wi, ns), co = dot(wo, ns);
        if (ci <= 0.0f) return;
        dir = wi;
        specular = false;
        prev_pdf = probs.x * pdf;
        pw_scatter_diagonal(&p, 0, surf.g * 2.0f * ci / (ci + co) / probs.x);
      }
    } else if (choice < probs.x + probs.y) {
      dir = sample_cosine_hemisphere(ns, u1, u2);
      specular = false;
      prev_pdf = probs.y * cosine_hemisphere_pdf(dot(dir, ns));
      pw_scatter_diagonal(&p, surf.rho, 1.0f / probs.y);
#if KASHA_FLUORESCENCE
    } else if (choice < probs.x + probs.y + probs.z) {
      dir = sample_cosine_hemisphere(ns, u1, u2);
      specular = false;
      prev_pdf = probs.z * cosine_hemisphere_pdf(dot(dir, ns));
      pw_scatter_fluorescent(&p, s->cmf, surf.ehat, surf.a, 1.0f / probs.z);
#endif
    } else {
      return; /* absorbed */
    }
    org = x + ns * s->ray_eps;
  }
}

__kernel void render_backward(KCamera camera, KASHA_SCENE_PARAMS, __global const float* cmf,
                              __global const float* importance, float ray_eps,
                              __global float* film,    /* pixels x KASHA_FILM_ROWS, sums over the pass */
                              __global int* rejected,  /* per pixel: samples that were not finite */
                              int spp, uint seed, uint pass) {
  int pixel = get_global_id(0);
  if (pixel >= camera.width * camera.height) return;
  SceneView s = {nodes, tris, materials, spectra, lobes, emitter_radiance, emitter_area_pdf, light_tri,
                 light_cdf, light_count, cmf, importance, ray_eps};
  int px = pixel % camera.width, py = pixel / camera.width;
  Rng rng = rng_seed(seed, pass, (uint)pixel);
  float sum[KASHA_FILM_ROWS];
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) sum[r] = 0.0f;
  int bad = 0;
  float3 org = camera_position(&camera);
  for (int k = 0; k < spp; ++k) {
    float3 dir = camera_direction(&camera, px + rng_next_float(&rng), py + rng_next_float(&rng));
    float rows[KASHA_FILM_ROWS];
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) rows[r] = 0.0f;
    trace_camera_path(&s, org, dir, &rng, rows);
    bool finite = true;
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) finite = finite && isfinite(rows[r]);
    if (!finite) {
      ++bad;
      continue;
    }
    for (int r = 0; r < KASHA_FILM_ROWS; ++r) sum[r] += rows[r];
  }
  for (int r = 0; r < KASHA_FILM_ROWS; ++r) film[pixel * KASHA_FILM_ROWS + r] = sum[r];
  rejected[pixel] = bad;
}
