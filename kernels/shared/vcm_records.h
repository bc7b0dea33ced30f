/* The records of vertex connection and merging (kernels/vcm/), shared by the host
 * (host/integrators/vcm/) and the kernels: each layout exists once, here, as named fields of
 * 4-byte scalars (shared_types.h's rule, so both compilers lay them out alike). */
#ifndef KASHA_VCM_RECORDS_H
#define KASHA_VCM_RECORDS_H

#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
namespace kasha {
#endif

/* A stored light vertex, followed in the store by its power per bin (N floats, with the arrival
 * half of the shading-normal correction): what connections, merges and Georgiev's MIS recursion
 * need of a light subpath's vertex. Its first eight fields are a photon's head (photon_layout.h),
 * so the hashed grid (hash_grid.cl) places and orders light vertices as it does photons. */
typedef struct {
  float position[3];
  float normal[3]; /* geometric, on the side the light arrived from */
  int path;        /* the light subpath's index in the iteration: with depth, a cell's order */
  int depth;       /* the bounce it was stored at */
  float arrival[3];     /* the direction the light travelled to arrive */
  float dvcm, dvc, dvm; /* the light subpath's partial MIS weights (SmallVCM's names) */
  int triangle;         /* the hit's triangle, leaf order */
  float eps;            /* the hit's offset */
  int previous;  /* the record of the subpath's previous stored vertex (-1: none): a camera path
                  * walks its light subpath from the last stored vertex back */
  int ordinal;   /* among the subpath's stored vertices (0: the first) */
  float barycentrics[2]; /* of the hit, for textures */
  int flags; /* KASHA_VCM_MERGEABLE: merges may use it (not at a rough interface, which only
              * connects, nor with caustic merges where the light came by no delta bounce);
              * KASHA_VCM_FRONT: the light arrived on the triangle's front side;
              * KASHA_VCM_MEDIUM: it lies in a medium */
  float shading[3]; /* the shading normal on the light's side */
  int instance;     /* the instance the hit was in (KASHA_INSTANCES; else -1) */
  int medium;       /* KASHA_VCM_MEDIUM: the medium it collided in (normals 0, triangle -1) */
  int pad[2];
} KVcmLightVertex;
KASHA_STATIC_SIZE(KVcmLightVertex, 112);

#define KASHA_VCM_MERGEABLE 1
#define KASHA_VCM_FRONT 2
#define KASHA_VCM_MEDIUM 4 /* a collision in a scattering medium, no surface (kernels/vcm/vcm_media.h) */

/* Floats of a stored light vertex with its power over `bins` bins: the store's stride. */
#define KASHA_VCM_VERTEX_FLOATS(bins) ((int)(sizeof(KVcmLightVertex) / sizeof(float)) + (bins))

/* Per light subpath of the store's chunk: its last stored vertex (-1: none) and the power the
 * depth guard cut from it, per its start. */
typedef struct {
  int last;
  float cut;
} KVcmLightPath;
KASHA_STATIC_SIZE(KVcmLightPath, 8);

/* Counters of the light pass: vertices it meant to store (beyond the capacity: not written, the
 * host grows the store and runs the chunk again) and splats the light paths' film rejected. */
typedef struct {
  int stored;
  int overflow;
} KVcmCounters;
KASHA_STATIC_SIZE(KVcmCounters, 8);

/* Per pixel of the camera pass: 1 where the light seen through delta bounces alone has an edge
 * (its extra samples, vcm_seen_light; the host's probe sets it), then the pass's rejected samples
 * and what the depth guard cut from its camera paths. */
typedef struct {
  int seen;
  int rejected;
  float cut;
} KVcmPixel;
KASHA_STATIC_SIZE(KVcmPixel, 12);

/* An iteration's merging radius: one for every vertex (per_unit 0: --radius, --merges every), or
 * (per_unit > 0) a pixel's footprint where the camera path merges — per_unit times the distance it
 * travelled there, through delta bounces — up to `radius`. η = eta_unit · r² with eta_unit = κ π
 * L over the pixel's camera paths (the host's kMergeWeight κ weighs merges down where connections
 * also reach a path). */
typedef struct {
  float eta_unit, radius, per_unit;
} KVcmRadius;
KASHA_STATIC_SIZE(KVcmRadius, 12);

/* What one launch of either pass takes besides the scene, the film and its buffers. */
typedef struct {
  KVcmRadius radius;
  float inv_cell;  /* the hashed grid's 1 / cell size */
  uint mask;       /* its hash mask (merging modes) */
  int paths;       /* light subpaths in the iteration */
  int chunk_first; /* the store holds light subpaths [chunk_first, chunk_end) */
  int chunk_end;
  int capacity;     /* records the store holds */
  int spp;          /* camera paths a pixel */
  int seen_samples; /* vcm_seen_light's samples a camera path, where a pixel's `seen` is set */
  int film_shift;   /* the light paths' fixed-point film's scale (fixed_point_film.h) */
  uint seed, pass;
} KVcmIteration;
KASHA_STATIC_SIZE(KVcmIteration, 56);

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
