/* Perlin's gradient noise as pbrt-v4 computes it (util/noise.cpp: Noise, FBm, Turbulence), shared by
 * the kernels' texture programs and the host's reference, so both give pbrt-v4's values. kasha has
 * no ray differentials: FBm and Turbulence take pbrt-v4's branch for a zero footprint (every octave,
 * no fading partial octave; Turbulence adds its 0.2·ω^octaves as pbrt-v4 does there), where pbrt-v4
 * drops the octaves finer than a pixel. The permutation is Ken Perlin's reference table. */
#ifndef KASHA_PERLIN_NOISE_H
#define KASHA_PERLIN_NOISE_H

#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
#include <cmath>
namespace kasha {
#define KASHA_NOISE_TABLE static const int
#define KASHA_NOISE_FLOOR std::floor
#define KASHA_NOISE_FMOD std::fmod
#define KASHA_NOISE_ABS std::fabs
#else
#define KASHA_NOISE_TABLE __constant int
#define KASHA_NOISE_FLOOR floor
#define KASHA_NOISE_FMOD fmod
#define KASHA_NOISE_ABS fabs
#endif

KASHA_NOISE_TABLE kasha_noise_perm[256] = {
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
};

/* pbrt-v4 stores the table twice so perm[perm[x] + y] needs no wrap; & 255 does the same. */
inline int noise_perm(int i) { return kasha_noise_perm[i & 255]; }

inline float noise_grad(int x, int y, int z, float dx, float dy, float dz) {
  int h = noise_perm(noise_perm(noise_perm(x) + y) + z) & 15;
  float u = h < 8 || h == 12 || h == 13 ? dx : dy;
  float v = h < 4 || h == 12 || h == 13 ? dy : dz;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

inline float noise_weight(float t) {
  float t3 = t * t * t;
  return 6.0f * t3 * t * t - 15.0f * t3 * t + 10.0f * t3;
}

inline float noise_lerp(float t, float a, float b) { return (1.0f - t) * a + t * b; }

/* pbrt-v4's Noise(x, y, z): in [-1, 1], zero at the integer lattice. */
inline float perlin_noise(float x, float y, float z) {
  x = KASHA_NOISE_FMOD(x, 1073741824.0f);
  y = KASHA_NOISE_FMOD(y, 1073741824.0f);
  z = KASHA_NOISE_FMOD(z, 1073741824.0f);
  int ix = (int)KASHA_NOISE_FLOOR(x), iy = (int)KASHA_NOISE_FLOOR(y), iz = (int)KASHA_NOISE_FLOOR(z);
  float dx = x - (float)ix, dy = y - (float)iy, dz = z - (float)iz;
  ix &= 255;
  iy &= 255;
  iz &= 255;
  float w000 = noise_grad(ix, iy, iz, dx, dy, dz);
  float w100 = noise_grad(ix + 1, iy, iz, dx - 1.0f, dy, dz);
  float w010 = noise_grad(ix, iy + 1, iz, dx, dy - 1.0f, dz);
  float w110 = noise_grad(ix + 1, iy + 1, iz, dx - 1.0f, dy - 1.0f, dz);
  float w001 = noise_grad(ix, iy, iz + 1, dx, dy, dz - 1.0f);
  float w101 = noise_grad(ix + 1, iy, iz + 1, dx - 1.0f, dy, dz - 1.0f);
  float w011 = noise_grad(ix, iy + 1, iz + 1, dx, dy - 1.0f, dz - 1.0f);
  float w111 = noise_grad(ix + 1, iy + 1, iz + 1, dx - 1.0f, dy - 1.0f, dz - 1.0f);
  float wx = noise_weight(dx), wy = noise_weight(dy), wz = noise_weight(dz);
  float y0 = noise_lerp(wy, noise_lerp(wx, w000, w100), noise_lerp(wx, w010, w110));
  float y1 = noise_lerp(wy, noise_lerp(wx, w001, w101), noise_lerp(wx, w011, w111));
  return noise_lerp(wz, y0, y1);
}

/* pbrt-v4's FBm with a zero footprint: octaves of noise, each 1.99× finer and ω× weaker. */
inline float perlin_fbm(float x, float y, float z, float omega, int octaves) {
  float sum = 0.0f, lambda = 1.0f, o = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += o * perlin_noise(lambda * x, lambda * y, lambda * z);
    lambda *= 1.99f;
    o *= omega;
  }
  return sum;
}

/* pbrt-v4's Turbulence with a zero footprint: octaves of |noise|, then the 0.2 it gives the
 * partial octave it would fade in. */
inline float perlin_turbulence(float x, float y, float z, float omega, int octaves) {
  float sum = 0.0f, lambda = 1.0f, o = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += o * KASHA_NOISE_ABS(perlin_noise(lambda * x, lambda * y, lambda * z));
    lambda *= 1.99f;
    o *= omega;
  }
  return sum + o * 0.2f;
}

#undef KASHA_NOISE_TABLE
#undef KASHA_NOISE_FLOOR
#undef KASHA_NOISE_FMOD
#undef KASHA_NOISE_ABS

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
