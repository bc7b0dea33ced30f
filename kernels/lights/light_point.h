/* A light sample's point (LightPoint): where next-event estimation and light paths start, with
 * what its spectrum needs; and which emitting triangle a leaf triangle is. Shared by lights.h and
 * sphere_light.h, below both. */
#ifndef KASHA_LIGHT_POINT_H
#define KASHA_LIGHT_POINT_H

#include "geometry/scene_view.h"
#include "lights/environment.h"
#include "materials/texture.h"

#ifndef KASHA_LIGHT_SOURCES
#define KASHA_LIGHT_SOURCES 0 /* some light is not a triangle (KLight) */
#endif

typedef struct {
  float3 position;
  float3 normal; /* front side */
  int emitter;   /* the row of emitter_radiance */
  float eps; /* the point's rounding bound along the normal (hit_point.h's surface_offset) */
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  float scale; /* on the spectrum: a point light's 1/d², a spot's falloff, an emission texture */
#endif
#if KASHA_LIGHT_SOURCES
  bool delta; /* no other strategy can find it: a point, a spot, a distant light */
  const __global KLight* source; /* the light that is not a triangle, else null */
#endif
#if KASHA_ENVIRONMENT
  const __global float* le; /* an environment texel's radiance (the scratch spectrum), else null */
#endif
} LightPoint;

/* A light point at `position` facing `normal`, of emitter row `emitter` (-1: none) and eps 0, its
 * other fields neutral (scale 1, no delta light, no source, no environment texel): where a light
 * sample starts, and what a failed one returns. */
inline LightPoint light_point(float3 position, float3 normal, int emitter) {
  LightPoint p;
  p.position = position;
  p.normal = normal;
  p.emitter = emitter;
  p.eps = 0.0f;
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  p.scale = 1.0f;
#endif
#if KASHA_LIGHT_SOURCES
  p.delta = false;
  p.source = 0;
#endif
#if KASHA_ENVIRONMENT
  p.le = 0;
#endif
  return p;
}

/* The spectral radiance (or intensity, irradiance) of the light point. */
inline const __global float* light_point_spectrum(const SceneView* s, const LightPoint* p) {
#if KASHA_ENVIRONMENT
  if (p->le) return p->le;
#endif
  return emitter_spectrum(s, p->emitter);
}

/* The index of emitting triangle `tri` (leaf order) among the emitting triangles, which light_tri
 * lists in ascending order; -1 when it is not one (it emits nothing). */
inline int emitting_index(const SceneView* s, int tri) {
  int lo = 0, hi = s->light_triangles - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (s->light_tri[mid] < tri) lo = mid + 1;
    else hi = mid;
  }
  return hi >= 0 && s->light_tri[lo] == tri ? lo : -1;
}

#endif
