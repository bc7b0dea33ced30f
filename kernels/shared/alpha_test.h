/* Alpha cut-outs (docs/formats.md#alpha), shared by the kernels' traversal and the host's Embree
 * reference: a candidate hit on a triangle whose shape has alpha a < 1 is kept only where a
 * uniform value from a hash of the ray and the triangle is below a (pbrt-v4's stochastic alpha
 * test); a <= 0 drops every hit. pbrt-v4 hashes the ray that reaches each candidate; the triangle's
 * scene index stands in for that ray's advance here, since a hit distance differs by rounding
 * between the two traversals while the index does not. */
#ifndef KASHA_ALPHA_TEST_H
#define KASHA_ALPHA_TEST_H

#include "shared/texture_program.h"

#ifndef __OPENCL_VERSION__
#include <cstring>
namespace kasha {
inline uint alpha_float_bits(float f) {
  uint u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
#else
inline uint alpha_float_bits(float f) { return as_uint(f); }
#endif

/* The tables a test reads; one triangle index addresses tris and texcoords alike (leaf order on
 * the device, scene order in Embree's reference). */
typedef struct {
  const KASHA_GLOBAL KTriangle* tris;
  const KASHA_GLOBAL KTexcoords* texcoords;
  const KASHA_GLOBAL KTexture* textures;
  const KASHA_GLOBAL float* values; /* an image's scalar texels */
  const KASHA_GLOBAL KTexOp* ops;   /* texture programs' steps */
} AlphaTables;

/* MurmurHash3's 64-bit finalizer over each of the n words in turn: a uniform value in [0, 1)
 * (the alpha test's and the mixes' choices). */
inline float hash_words(const uint* words, int n) {
  ulong h = 0x9e3779b97f4a7c15UL;
  for (int k = 0; k < n; ++k) {
    h ^= (ulong)words[k];
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdUL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53UL;
    h ^= h >> 33;
  }
  return (float)(uint)(h >> 40) * 0x1p-24f;
}

/* The alpha test's value from the ray (origin, direction) and the triangle's scene index. */
inline float alpha_hash(const float* ray, int prim) {
  uint words[7];
  for (int k = 0; k < 6; ++k) words[k] = alpha_float_bits(ray[k]);
  words[6] = (uint)prim;
  return hash_words(words, 7);
}

/* The alpha at barycentrics (b1, b2) of triangle tri: 1 for a shape without one. */
inline float alpha_at(const AlphaTables* a, int tri, float b1, float b2) {
  const KASHA_GLOBAL KTexcoords* c = &a->texcoords[tri];
  if (c->alpha_texture < 0) return 1.0f;
  float b0 = 1.0f - b1 - b2;
  float u = b0 * c->uv[0] + b1 * c->uv[2] + b2 * c->uv[4], v = b0 * c->uv[1] + b1 * c->uv[3] + b2 * c->uv[5];
  const KASHA_GLOBAL KTexture* t = &a->textures[c->alpha_texture];
#if KASHA_TEXTURE_PROGRAMS
  if (t->type == KASHA_TEXTURE_PROGRAM) {
    TexPoint at = triangle_tex_point(&a->tris[tri], c, b1, b2);
    TexTables tt = {a->textures, a->ops, a->values};
    return texture_scalar_at(&tt, t, &at);
  }
#endif
  return texture_scalar_uv(t, a->values, u, v);
}

/* Whether the candidate hit at (b1, b2) of triangle tri by the ray (origin, direction: 6 floats)
 * survives the alpha test. */
inline bool alpha_keeps(const AlphaTables* a, int tri, float b1, float b2, const float* ray) {
  float alpha = alpha_at(a, tri, b1, b2);
  if (alpha >= 1.0f) return true;
  if (!(alpha > 0.0f)) return false;
  return alpha_hash(ray, a->tris[tri].prim) < alpha;
}

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
