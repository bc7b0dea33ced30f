/* A hit's material as every path sees it: a mix's choice (mix.h) and the chosen material's normal
 * map (normal_map.h), resolved where the hit is made, so camera paths, light paths and vcm's stored
 * light vertices see one material and one shading normal at a point. */
#ifndef KASHA_HIT_MATERIAL_H
#define KASHA_HIT_MATERIAL_H

#include "geometry/hit_point.h"
#include "geometry/scene_view.h"
#include "materials/mix.h"
#include "materials/normal_map.h"

/* The closest hit along the ray (intersect_scene) with its material resolved: a mix's choice, the
 * normal map's shading normal, and a coat's cosine to that normal. */
inline bool intersect_surface(const SceneView* s, float3 org, float3 dir, HitPoint* h) {
  if (!intersect_scene(s, org, dir, h)) return false;
#if KASHA_MIX
  h->material = resolve_material(s, h->material, h->x, h->tri, h->b);
#endif
#if KASHA_NORMAL_MAPS
  /* The material's normal map, once the mix has chosen it. */
  int map = h->material >= 0 ? s->materials[h->material].normal_map : -1;
  if (map >= 0) {
    h->nf = normal_map_normal(s, &s->textures[map], h->tri, h->b, hit_dpdu(s, h), h->nf, h->n);
    h->ns = h->front ? h->nf : -h->nf;
  }
#endif
#if KASHA_COATED
  h->cos_in = fmax(0.0f, -dot(h->ns, dir));
#endif
  return true;
}

#endif
