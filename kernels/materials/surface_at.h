/* The surface at a hit as every integrator uses it: the material, its textures applied
 * (texture.h), and a coat set up for the side the ray arrived from (coat.h). */
#ifndef KASHA_SURFACE_AT_H
#define KASHA_SURFACE_AT_H

#include "materials/coat.h"
#include "geometry/hit_point.h"
#include "materials/surface.h"
#include "materials/texture.h"

inline void load_surface_at(const SceneView* s, const HitPoint* h, Surface* surf) {
  load_textured_surface(s, h, surf);
#if KASHA_ANISOTROPIC
  surf->dpdu = hit_dpdu(s, h);
#endif
#if KASHA_COATED
  if (surf->coated) coat_at(s, surf, h->cos_in);
#endif
}

#endif
