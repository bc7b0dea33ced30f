/* The scene as every kernel sees it: camera, BVH, materials and their spectra, emitters and the
 * light-sampling tables with the lights that are not triangles. Kernels take KASHA_SCENE_PARAMS first (DeviceScene::bind sets them in
 * this order) and gather them into one SceneView with KASHA_SCENE_VIEW, which every routine takes. */
#ifndef KASHA_SCENE_VIEW_H
#define KASHA_SCENE_VIEW_H

#include "shared_types.h"

#ifndef KASHA_SCRATCH_FLOATS
#define KASHA_SCRATCH_FLOATS 0
#endif

/* The rays a work item traced, counted in private memory and added to the launch's totals once at
 * its end (add_ray_counts, hit_point.h): bench's rays/s, at the cost of an increment per ray. */
typedef struct {
  uint closest, shadow;
} RayCounts;

typedef struct {
  KCamera camera;
  const __global KBvhNode* nodes;
  const __global KBvhLeaf* leaves; /* the BVH's triangles, precomputed for its traversal */
  const __global KTriangle* tris;
  const __global KMaterial* materials;
  const __global float* spectra; /* material spectra; the first N values are zeros */
  const __global float* lobes;
  const __global float* emitter_radiance; /* emitters × N */
  const __global float* emitter_area_pdf;
  const __global int* light_tri;
  const __global float* light_cdf;
  int light_count;
  float bin_nm;
  const __global KLight* lights; /* the lights that are not triangles (light_tri's ~k) */
  int light_sources;             /* how many */
  __global float* scratch; /* the work item's own KASHA_SCRATCH_FLOATS (spectra computed on the
                            * way: an environment texel's radiance, a textured reflectance), global
                            * like every spectrum */
  const __global KTexture* textures;
  const __global KTexcoords* texcoords; /* per leaf triangle, when textures need them */
  const __global KShadingNormals* normals; /* per leaf triangle, when some shape has them */
  RayCounts* rays; /* private: the work item's own counts */
} SceneView;

#define KASHA_SCENE_PARAMS                                                                                  \
  KCamera camera, __global const KBvhNode *nodes, __global const KBvhLeaf *leaves,                          \
      __global const KTriangle *tris, __global const KMaterial *materials, __global const float *spectra,   \
      __global const float *lobes, __global const float *emitter_radiance,                                  \
      __global const float *emitter_area_pdf, __global const int *light_tri,                                \
      __global const float *light_cdf, int light_count, float bin_nm, __global const KLight *lights,          \
      int light_sources, __global float *scratch, __global const KTexture *textures,                     \
      __global const KTexcoords *texcoords, __global const KShadingNormals *normals

#define KASHA_SCENE_VIEW(name)                                                                              \
  RayCounts name##_rays = {0u, 0u};                                                                         \
  SceneView name = {camera,           nodes,     leaves,    tris,        materials, spectra, lobes,         \
                    emitter_radiance, emitter_area_pdf, light_tri, light_cdf, light_count, bin_nm,        \
                    lights,           light_sources,                                                   \
                    scratch + (get_global_id(0) - get_global_offset(0)) * KASHA_SCRATCH_FLOATS,    \
                    textures,         texcoords,        normals,          &name##_rays}

/* An emitter's spectral radiance, N values. */
inline const __global float* emitter_spectrum(const SceneView* s, int emitter) {
  return s->emitter_radiance + emitter * KASHA_BINS;
}

#endif
