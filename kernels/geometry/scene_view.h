/* The scene as every kernel sees it: camera, BVH, materials and their spectra, emitters and the
 * light-sampling tables with the lights that are not triangles. Kernels take KASHA_SCENE_PARAMS first (DeviceScene::bind sets them in
 * this order) and gather them into one SceneView with KASHA_SCENE_VIEW, which every routine takes:
 * a kernel body reads the scene only through that view. */
#ifndef KASHA_SCENE_VIEW_H
#define KASHA_SCENE_VIEW_H

#include "geometry/bvh_traversal.h"
#include "shared/alpha_test.h"
#include "shared/shared_types.h"
#include "shared/texture_program.h"

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
  const __global int* light_tri;   /* the emitting triangles (ascending), then ~k of the lights */
  const __global float* light_cdf; /* by power: what photons and light paths leave */
  int light_count;
  const __global KLightNode* light_nodes; /* next-event estimation's choice of emitting triangle */
  const __global ulong* light_trails;     /* per emitting triangle, its path from the root */
  int light_triangles;                    /* how many emitting triangles light_tri starts with */
  const __global KSphereLight* light_spheres; /* per emitting triangle, its sphere light */
  float bin_nm;
  const __global KLight* lights; /* the lights that are not triangles (light_tri's ~k) */
  int light_sources;             /* how many */
  __global float* scratch; /* the work item's own KASHA_SCRATCH_FLOATS (spectra computed on the
                            * way: an environment texel's radiance, a textured reflectance), global
                            * like every spectrum */
  const __global KTexture* textures;
  const __global KTexcoords* texcoords; /* per leaf triangle, when textures need them */
  const __global KShadingNormals* normals; /* per leaf triangle, when some shape has them */
  const __global KInstance* instances;     /* KASHA_INSTANCES: the top level's leaves */
  const __global KTangent* tangents;       /* per leaf triangle, KASHA_ANISOTROPIC or KASHA_NORMAL_MAPS */
  const __global KTexOp* tex_ops;          /* texture programs' steps, KASHA_TEXTURE_PROGRAMS */
  const __global KMedium* media;           /* KASHA_MEDIA: the participating media */
  const __global KTriMedia* tri_media;     /* KASHA_MEDIA: per leaf triangle, its medium interface */
  int camera_medium;                       /* the medium the camera is in, -1: vacuum */
  float4 bounds; /* the triangles' bounding sphere: centre (xyz) and radius (w) */
  RayCounts* rays; /* private: the work item's own counts */
} SceneView;

/* The scene's tables lie in one buffer (scene_tables) at the offsets scene_params holds. */
#define KASHA_SCENE_PARAMS \
  KSceneParams scene_params, __global const uchar *scene_tables, __global float *scratch
#define KASHA_SCENE_TABLE(type, table) ((const __global type*)(scene_tables + scene_params.table))

#define KASHA_SCENE_VIEW(name)                                                                     \
  RayCounts name##_rays = {0u, 0u};                                                                \
  SceneView name = {scene_params.camera,                                                           \
                    KASHA_SCENE_TABLE(KBvhNode, nodes),                                            \
                    KASHA_SCENE_TABLE(KBvhLeaf, leaves),                                           \
                    KASHA_SCENE_TABLE(KTriangle, tris),                                            \
                    KASHA_SCENE_TABLE(KMaterial, materials),                                       \
                    KASHA_SCENE_TABLE(float, spectra),                                             \
                    KASHA_SCENE_TABLE(float, lobes),                                               \
                    KASHA_SCENE_TABLE(float, emitter_radiance),                                    \
                    KASHA_SCENE_TABLE(float, emitter_area_pdf),                                    \
                    KASHA_SCENE_TABLE(int, light_tri),                                             \
                    KASHA_SCENE_TABLE(float, light_cdf),                                           \
                    scene_params.light_count,                                                      \
                    KASHA_SCENE_TABLE(KLightNode, light_nodes),                                    \
                    KASHA_SCENE_TABLE(ulong, light_trails),                                        \
                    scene_params.light_triangles,                                                  \
                    KASHA_SCENE_TABLE(KSphereLight, light_spheres),                                \
                    scene_params.bin_nm,                                                           \
                    KASHA_SCENE_TABLE(KLight, lights),                                             \
                    scene_params.light_sources,                                                    \
                    scratch + get_global_id(0) * KASHA_SCRATCH_FLOATS,                            \
                    KASHA_SCENE_TABLE(KTexture, textures),                                         \
                    KASHA_SCENE_TABLE(KTexcoords, texcoords),                                      \
                    KASHA_SCENE_TABLE(KShadingNormals, normals),                                   \
                    KASHA_SCENE_TABLE(KInstance, instances),                                       \
                    KASHA_SCENE_TABLE(KTangent, tangents),                                         \
                    KASHA_SCENE_TABLE(KTexOp, tex_ops),                                            \
                    KASHA_SCENE_TABLE(KMedium, media),                                             \
                    KASHA_SCENE_TABLE(KTriMedia, tri_media),                                       \
                    scene_params.camera_medium,                                                    \
                    (float4)(scene_params.scene_center[0], scene_params.scene_center[1],           \
                             scene_params.scene_center[2], scene_params.scene_radius),             \
                    &name##_rays}

/* The tables the traversal's alpha test reads (shared/alpha_test.h): leaf order. */
inline AlphaTables scene_alpha(const SceneView* s) {
  AlphaTables a = {s->tris, s->texcoords, s->textures, s->spectra, s->tex_ops};
  return a;
}

/* The tables a texture program reads (shared/texture_program.h). */
inline TexTables scene_texture_tables(const SceneView* s) {
  TexTables tt = {s->textures, s->tex_ops, s->spectra};
  return tt;
}

/* The tables the traversal reads. */
inline BvhTables scene_bvh(const SceneView* s) {
  BvhTables b = {s->nodes, s->leaves, s->instances};
  return b;
}

/* An emitter's spectral radiance, N values. */
inline const __global float* emitter_spectrum(const SceneView* s, int emitter) {
  return s->emitter_radiance + emitter * KASHA_BINS;
}

#endif
