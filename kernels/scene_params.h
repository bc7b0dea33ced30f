/* The scene's buffers as every kernel takes them, in the order DeviceScene::bind sets them. */
#ifndef KASHA_SCENE_PARAMS_H
#define KASHA_SCENE_PARAMS_H

#include "shared_types.h"

#define KASHA_SCENE_PARAMS                                                                           \
  __global const KBvhNode *nodes, __global const KTriangle *tris, __global const KMaterial *materials, \
      __global const float *spectra, __global const float *lobes, __global const float *emitter_radiance, \
      __global const float *emitter_area_pdf, __global const int *light_tri, __global const float *light_cdf, \
      int light_count

#endif
