/* Next-event estimation (docs/design.md#backward-transport): at a camera path's vertex, one point on an emitting
 * triangle (by solid angle where it subtends enough) or one of the other lights (docs/lights.md), its light through the surface's parts —
 * passive, fluorescent (K applied to the light's spectrum: rank-1 through ê aᵀ), the gloss lobe —
 * each weighed by MIS against the branch that could also have hit the light. Shared by backward
 * and photon mapping's camera pass. */
#ifndef KASHA_NEXT_EVENT_H
#define KASHA_NEXT_EVENT_H

#include "materials/coat.h"
#include "film/film_view.h"
#include "materials/gloss_lobe.h"
#include "geometry/hit_point.h"
#include "lights/lights.h"
#include "film/path_weight.h"
#include "sampling/sampling.h"
#include "geometry/scene_view.h"
#include "materials/surface.h"
#include "media/medium.h"

/* probs: the branch probabilities (gloss, passive, fluorescent) of the strategies that could also
 * reach the light from x; 0 for a part whose branch never continues to an emitter (photon mapping
 * ends camera paths at their Lambert vertex), which then takes the whole light sample.
 * At the hit h (wo towards the viewer, who arrived in `medium`): rows += T·(light). */
inline void next_event(const PathWeight* p, const SceneView* s, const FilmView* f, const Surface* surf,
                       const HitPoint* h, int medium, float3 wo, float3 probs, float2 u_light, float* rows) {
  float3 x = h->x, ns = h->ns, ng = hit_ng(h);
  float eps = h->eps;
  float pdf_light;
  LightPoint lp = sample_light_from(s, x, u_light, &pdf_light);
  if (!(pdf_light > 0.0f)) return;
  float3 to = lp.position - x;
  float dist = length(to);
  if (!(dist > eps + lp.eps)) return;
  float3 wi = to / dist;
  float cos_x = dot(ns, wi), cos_l = -dot(lp.normal, wi);
  bool through = false;
#if KASHA_TRANSMISSION
  /* A light behind a transmitting surface reaches it through its τ (surface.h). */
  if (cos_x < 0.0f && surf->share_t > 0.0f) {
    through = true;
    cos_x = -cos_x;
    ns = -ns;
    ng = -ng;
  }
#endif
  if (cos_x <= 0.0f || cos_l <= 0.0f) return;
#if KASHA_SHADING_NORMALS
  /* A light behind the geometric surface does not reach it, whatever the shading normal says. */
  if (dot(ng, wi) <= 0.0f) return;
#endif
  /* The light point's rounding along its normal is lp.eps: along a ray meeting its surface at
   * cos_l it is lp.eps / cos_l, what the shadow ray must stop short by (at grazing angles the
   * light's own surface would block it otherwise). */
  const __global float* le = light_point_spectrum(s, &lp);
#if KASHA_MEDIA
  le = segment_light(s, x, ng, eps, wi, dist, lp.eps / cos_l, medium_after(s, h->tri, h->n, wi, medium), le);
  if (!le) return;
#else
  if (segment_occluded(s, x, ng, eps, wi, dist, lp.eps / cos_l)) return;
#endif
  float lambert_pdf = cosine_hemisphere_pdf(cos_x);
  float base = cos_x / pdf_light;
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  base *= lp.scale;
#endif
#if KASHA_COATED
  /* Through a coat, t(θo) t(θi) / η² (coat.h); its mirror lobe sees no light point. */
  float lambert_base = base * surface_lambert_weight(surf, cos_x);
#else
  const float lambert_base = base;
#endif
#if KASHA_LIGHT_SOURCES
  /* A delta light (point, spot, distant) no bounce can hit: its sample takes the whole weight. */
  float reach = lp.delta ? 0.0f : 1.0f;
#else
  const float reach = 1.0f;
#endif
  float side = surface_side_share(surf, through);
  if (surf->passive)
    pw_add(p, f, surface_side_spectrum(surf, through), le,
           lambert_base * KASHA_INV_PI * mis_weight(pdf_light, reach * probs.y * side * lambert_pdf), rows);
  if (through) return; /* a transmitting material has no other part (host/material) */
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) {
    float absorbed = spectrum_dot(KASHA_BINS, 0, surf->a, le);
    pw_add(p, f, surf->ehat, 0,
           absorbed * lambert_base * KASHA_INV_PI * mis_weight(pdf_light, reach * probs.z * lambert_pdf), rows);
  }
#endif
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    /* A rough coat's GGX lobe (coat.h), about the normal on the viewer's side. */
    Frame fr = frame_of(ns);
    float pdf;
    float fc = coat_lobe_eval(surf, to_local(&fr, wo), to_local(&fr, wi), &pdf);
    if (fc > 0.0f) pw_add(p, f, le, 0, fc * base * mis_weight(pdf_light, reach * probs.x * pdf), rows);
    return;
  }
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) {
    float fg = lobe_brdf(surf->m, s->lobes, wo, wi, ns);
    if (fg > 0.0f) {
      float lobe = lobe_pdf(surf->m, s->lobes, dot(wi, reflect_dir(-wo, ns)));
      pw_add(p, f, le, 0, surf->g * fg * base * mis_weight(pdf_light, reach * probs.x * lobe), rows);
    }
  }
#endif
}

#endif
