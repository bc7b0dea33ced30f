/* The lookups of a texture that need no spectra (docs/textures.md), shared by the kernels and the
 * host: the texels an image blends at (s, t) after wrapping, a checkerboard's square, and a scalar
 * texture's value. The host's Embree reference evaluates alpha cut-outs with these, so both sides
 * agree to the bit. Lookups follow pbrt-v4: (s, t) = (u·uscale + udelta, v·vscale + vdelta); an
 * image's t runs up from its bottom row; bilinear between texel centres or the nearest texel;
 * wrap by repeating, clamping, black outside [0, 1)², or mirrored as pbrt-v4's octahedral sphere. */
#ifndef KASHA_TEXTURE_LOOKUP_H
#define KASHA_TEXTURE_LOOKUP_H

#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
#include <algorithm>
#include <cmath>
namespace kasha {
#define KASHA_FLOOR std::floor
#define KASHA_CLAMP std::clamp
#else
#define KASHA_FLOOR floor
#define KASHA_CLAMP clamp
#endif

/* The texel (x, y) after wrapping; -1 where a black wrap leaves the image. */
inline int texel_index(const KASHA_GLOBAL KTexture* t, int x, int y) {
  int w = t->width, h = t->height;
  if (t->wrap == KASHA_WRAP_REPEAT) {
    x %= w;
    y %= h;
    if (x < 0) x += w;
    if (y < 0) y += h;
  } else if (t->wrap == KASHA_WRAP_OCTAHEDRAL) {
    /* pbrt-v4's RemapPixelCoords: across a vertical edge mirrored in u and in v about its middle,
     * across a horizontal edge likewise; clamped after for lookups further out. */
    if (x < 0 || x >= w) {
      x = x < 0 ? -x : 2 * w - 1 - x;
      y = h - 1 - y;
    }
    if (y < 0 || y >= h) {
      y = y < 0 ? -y : 2 * h - 1 - y;
      x = w - 1 - x;
    }
    x = KASHA_CLAMP(x, 0, w - 1);
    y = KASHA_CLAMP(y, 0, h - 1);
  } else if (t->wrap == KASHA_WRAP_CLAMP) {
    x = KASHA_CLAMP(x, 0, w - 1);
    y = KASHA_CLAMP(y, 0, h - 1);
  } else if (x < 0 || y < 0 || x >= w || y >= h) {
    return -1;
  }
  return y * w + x;
}

/* The texels an image lookup at (s, t) blends and their weights; how many (1 or 4). */
inline int texture_taps_st(const KASHA_GLOBAL KTexture* t, float s, float tt, int* idx, float* w) {
  /* Image rows run down from the top; t runs up (pbrt-v4's 1 − t). Large s, t stay finite: the
   * floor is taken in float, then wrapped in int range. */
  float x = s * (float)t->width, y = (1.0f - tt) * (float)t->height;
  x = KASHA_CLAMP(x, -1e8f, 1e8f);
  y = KASHA_CLAMP(y, -1e8f, 1e8f);
  if (!t->bilinear) {
    idx[0] = texel_index(t, (int)KASHA_FLOOR(x), (int)KASHA_FLOOR(y));
    w[0] = 1.0f;
    return 1;
  }
  x -= 0.5f;
  y -= 0.5f;
  float fx0 = KASHA_FLOOR(x), fy0 = KASHA_FLOOR(y), fx = x - fx0, fy = y - fy0;
  int x0 = (int)fx0, y0 = (int)fy0;
  idx[0] = texel_index(t, x0, y0);
  idx[1] = texel_index(t, x0 + 1, y0);
  idx[2] = texel_index(t, x0, y0 + 1);
  idx[3] = texel_index(t, x0 + 1, y0 + 1);
  w[0] = (1.0f - fx) * (1.0f - fy);
  w[1] = fx * (1.0f - fy);
  w[2] = (1.0f - fx) * fy;
  w[3] = fx * fy;
  return 4;
}

inline bool checker_odd_st(float s, float t) {
  float fs = KASHA_FLOOR(KASHA_CLAMP(s, -1e8f, 1e8f)), ft = KASHA_FLOOR(KASHA_CLAMP(t, -1e8f, 1e8f));
  return (((int)fs + (int)ft) & 1) != 0;
}

/* A scalar texture's value at (u, v); an image's texels (one float each) lie in `values`. */
inline float texture_scalar_uv(const KASHA_GLOBAL KTexture* t, const KASHA_GLOBAL float* values, float u, float v) {
  float s = u * t->uscale + t->udelta, tt = v * t->vscale + t->vdelta;
  if (t->type == KASHA_TEXTURE_CHECKERBOARD) return checker_odd_st(s, tt) ? t->odd_value : t->even_value;
  int idx[4];
  float w[4], r = 0.0f;
  int n = texture_taps_st(t, s, tt, idx, w);
  for (int k = 0; k < n; ++k)
    if (idx[k] >= 0) r += w[k] * values[t->data + idx[k]];
  return r;
}

#undef KASHA_FLOOR
#undef KASHA_CLAMP

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
