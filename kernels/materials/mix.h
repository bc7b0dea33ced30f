/* pbrt-v4's MixMaterial (docs/materials.md#mixes): at each point of a mix's surface one of its two
 * materials, the second where amount ≥ u, u uniform from a hash; nested mixes in turn. pbrt-v4
 * hashes the point and the viewing direction; kasha hashes the point alone (and the two
 * materials), so a camera path, a light path and vcm's stored light vertex that meet one point all
 * see one surface there, which bidirectional estimators need. Over a pixel the expectation is
 * the same blend (1 − amount)·first + amount·second. */
#ifndef KASHA_MIX_H
#define KASHA_MIX_H

#include "geometry/scene_view.h"
#include "shared/alpha_test.h"
#include "shared/texture_program.h"

#ifndef KASHA_MIX
#define KASHA_MIX 0 /* some shape's material is a mix */
#endif
#ifndef KASHA_TEXTURES
#define KASHA_TEXTURES 0
#endif

#if KASHA_MIX
/* A uniform value in [0, 1) from the point's coordinates and the mix's two materials. */
inline float mix_hash(float3 x, int a, int b) {
  uint words[5] = {as_uint(x.x), as_uint(x.y), as_uint(x.z), (uint)a, (uint)b};
  return hash_words(words, 5);
}

/* A mix's amount at barycentrics b of leaf triangle tri: its constant, or its texture's value. */
inline float mix_amount(const SceneView* s, const __global KMix* m, int tri, float2 b) {
#if KASHA_TEXTURES
  if (m->amount_texture >= 0) {
#if KASHA_TEXTURE_PROGRAMS
    const __global KTexture* tex = &s->textures[m->amount_texture];
    if (tex->type == KASHA_TEXTURE_PROGRAM) {
      TexPoint at = triangle_tex_point(&s->tris[tri], &s->texcoords[tri], b.x, b.y);
      TexTables tt = scene_texture_tables(s);
      return texture_scalar_at(&tt, tex, &at);
    }
#endif
    const __global float* t = s->texcoords[tri].uv;
    float b0 = 1.0f - b.x - b.y;
    return texture_scalar_uv(&s->textures[m->amount_texture], s->spectra, b0 * t[0] + b.x * t[2] + b.y * t[4],
                             b0 * t[1] + b.x * t[3] + b.y * t[5]);
  }
#endif
  return m->amount;
}
#endif

/* The material at point x (barycentrics b of leaf triangle tri) of a triangle whose material is
 * `material`: a mix resolved to one of its materials, as pbrt-v4's ChooseMaterial (amount ≤ 0:
 * the first, ≥ 1: the second), the host bounding the nesting by KASHA_MIX_DEPTH. */
inline int resolve_material(const SceneView* s, int material, float3 x, int tri, float2 b) {
#if KASHA_MIX
  for (int d = 0; d < KASHA_MIX_DEPTH && s->materials[material].kind == KASHA_KIND_MIX; ++d) {
    const __global KMix* m = &s->materials[material].mix;
    float amount = mix_amount(s, m, tri, b);
    int first = m->materials[0], second = m->materials[1];
    material = amount <= 0.0f ? first : amount >= 1.0f ? second : amount < mix_hash(x, first, second) ? first : second;
  }
#endif
  return material;
}

#endif
