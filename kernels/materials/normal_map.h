/* Normal maps (docs/materials.md#normal-maps): pbrt-v4's NormalMap (materials.h). The texel
 * blend's rgb at the hit's (u, v) (bilinear, repeating; t runs up from the bottom row as every
 * image lookup's) is the tangent-space normal 2·rgb − 1 in the frame x = ∂p/∂u made orthogonal to
 * the shading normal, y = n × x, z = n (Frame::FromXZ); pbrt-v4's SetShadingGeometry then turns it
 * to the geometric normal's side. Applied where a hit is made (materials/hit_material.h), so camera
 * and light paths, and vcm's stored light vertices, see one shading normal at a point. */
#ifndef KASHA_NORMAL_MAP_H
#define KASHA_NORMAL_MAP_H

#include "geometry/scene_view.h"
#include "sampling/sampling.h"
#include "shared/texture_lookup.h"

#ifndef KASHA_NORMAL_MAPS
#define KASHA_NORMAL_MAPS 0 /* some shape's material has a normal map */
#endif

#if KASHA_NORMAL_MAPS
/* The front shading normal that normal map t gives at barycentrics b of leaf triangle tri, whose
 * unmapped front shading normal is nf, geometric front normal n and ∂p/∂u dpdu (world space). */
inline float3 normal_map_normal(const SceneView* s, const __global KTexture* t, int tri, float2 b, float3 dpdu,
                                float3 nf, float3 n) {
  const __global float* c = s->texcoords[tri].uv;
  float b0 = 1.0f - b.x - b.y;
  float u = b0 * c[0] + b.x * c[2] + b.y * c[4], v = b0 * c[1] + b.x * c[3] + b.y * c[5];
  int idx[4];
  float w[4];
  int taps = texture_taps_st(t, u, v, idx, w);
  float3 rgb = (float3)(0.0f);
  for (int k = 0; k < taps; ++k) rgb += w[k] * vload3(idx[k], s->spectra + t->data);
  float3 tangent = 2.0f * rgb - 1.0f;
  /* A texel of (0.5, 0.5, 0.5) has no direction (pbrt-v4 would shade with NaN): left unmapped. */
  if (!(dot(tangent, tangent) > 0.0f)) return nf;
  float3 x = dpdu - nf * dot(nf, dpdu), y;
  float len = length(x);
  if (len > 0.0f) {
    x /= len;
    y = cross(nf, x);
  } else {
    basis_around(nf, &x, &y); /* pbrt-v4's CoordinateSystem where ∂p/∂u is degenerate */
  }
  float3 ns = normalize(tangent.x * x + tangent.y * y + tangent.z * nf);
  return dot(ns, n) < 0.0f ? -ns : ns;
}
#endif

#endif
