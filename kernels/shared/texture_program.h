/* Texture programs (docs/textures.md#textures-of-textures), shared by the kernels and the host: a
 * texture made of textures (pbrt-v4's mix, scale, directionmix, checkerboard and dots of textures,
 * bilerp, fbm, wrinkled, windy, marble, and every mapping) is compiled by the host
 * (host/render/texture_program.cpp) into KTexOp steps, each writing a slot from earlier slots, so
 * a tree is evaluated front to back without recursion and each shared subtree once. This file runs
 * the scalar steps; a spectral program's terms (slot × spectrum) are summed per bin by the
 * kernels' texture.h. Each step follows the pbrt-v4 texture or mapping it stands for. */
#ifndef KASHA_TEXTURE_PROGRAM_H
#define KASHA_TEXTURE_PROGRAM_H

#include "shared/perlin_noise.h"
#include "shared/texture_lookup.h"

/* Kernels compile programs in only for a scene that has one; the host always has them. */
#ifndef KASHA_TEXTURE_PROGRAMS
#ifdef __OPENCL_VERSION__
#define KASHA_TEXTURE_PROGRAMS 0
#else
#define KASHA_TEXTURE_PROGRAMS 1
#endif
#endif

#ifndef __OPENCL_VERSION__
#include <cmath>
namespace kasha {
#define KASHA_TP_FLOOR std::floor
#define KASHA_TP_SQRT std::sqrt
#define KASHA_TP_ATAN2 std::atan2
#define KASHA_TP_ACOS std::acos
#define KASHA_TP_SIN std::sin
#define KASHA_TP_FABS std::fabs
#define KASHA_TP_MIN std::min
#define KASHA_TP_MAX std::max
#else
#define KASHA_TP_FLOOR floor
#define KASHA_TP_SQRT sqrt
#define KASHA_TP_ATAN2 atan2
#define KASHA_TP_ACOS acos
#define KASHA_TP_SIN sin
#define KASHA_TP_FABS fabs
#define KASHA_TP_MIN min
#define KASHA_TP_MAX max
#endif

/* Where a texture is evaluated: the surface's (u, v), its point in world space and its geometric
 * normal (pbrt-v4's TextureEvalContext p, n, uv; render space and world space differ by a rigid
 * motion that the texture's own transform absorbs). */
typedef struct {
  float u, v;
  float p[3];
  float n[3];
} TexPoint;

/* The texture point at barycentrics (b1, b2) of a triangle (as stored: an instanced object's in
 * object space) with texture coordinates c. */
inline TexPoint triangle_tex_point(const KASHA_GLOBAL KTriangle* k, const KASHA_GLOBAL KTexcoords* c, float b1, float b2) {
  TexPoint at;
  float b0 = 1.0f - b1 - b2;
  at.u = b0 * c->uv[0] + b1 * c->uv[2] + b2 * c->uv[4];
  at.v = b0 * c->uv[1] + b1 * c->uv[3] + b2 * c->uv[5];
  float e1[3], e2[3];
  for (int i = 0; i < 3; ++i) {
    at.p[i] = b0 * k->v0[i] + b1 * k->v1[i] + b2 * k->v2[i];
    e1[i] = k->v1[i] - k->v0[i];
    e2[i] = k->v2[i] - k->v0[i];
  }
  float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  float len = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  len = len > 0.0f ? 1.0f / KASHA_TP_SQRT(len) : 0.0f;
  for (int i = 0; i < 3; ++i) at.n[i] = n[i] * len;
  return at;
}

/* The tables a program reads. */
typedef struct {
  const KASHA_GLOBAL KTexture* textures;
  const KASHA_GLOBAL KTexOp* ops;
  const KASHA_GLOBAL float* data; /* texels, spectra and matrices (the spectra buffer) */
} TexTables;

/* The point by the 3×4 matrix (row-major) at data[m]. */
inline void texture_point(const KASHA_GLOBAL float* M, const TexPoint* at, float* q) {
  for (int r = 0; r < 3; ++r) q[r] = M[4 * r] * at->p[0] + M[4 * r + 1] * at->p[1] + M[4 * r + 2] * at->p[2] + M[4 * r + 3];
}

/* pbrt-v4's InsidePolkaDot: a dot of radius 0.35 in about half the cells, jittered by noise. */
inline float polka_dot(float s, float t) {
  float sc = KASHA_TP_FLOOR(s + 0.5f), tc = KASHA_TP_FLOOR(t + 0.5f);
  if (!(perlin_noise(sc + 0.5f, tc + 0.5f, 0.5f) > 0.0f)) return 0.0f;
  const float radius = 0.35f, shift = 0.5f - 0.35f;
  float ds = s - (sc + shift * perlin_noise(sc + 1.5f, tc + 2.8f, 0.5f));
  float dt = t - (tc + shift * perlin_noise(sc + 4.5f, tc + 9.8f, 0.5f));
  return ds * ds + dt * dt < radius * radius ? 1.0f : 0.0f;
}

/* A 2D mapping's (s, t) into vals[dst], vals[dst + 1] (pbrt-v4's UV, spherical, cylindrical and
 * planar mappings). */
inline void texture_map_2d(const TexTables* tt, const KASHA_GLOBAL KTexOp* op, const TexPoint* at, float* vals) {
  float s, t;
  if (op->type == KASHA_TEXOP_MAP_UV) {
    s = at->u * op->f[0] + op->f[2];
    t = at->v * op->f[1] + op->f[3];
  } else {
    float q[3];
    texture_point(tt->data + op->ref, at, q);
    if (op->type == KASHA_TEXOP_MAP_SPHERE) {
      float len = KASHA_TP_SQRT(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
      float z = len > 0.0f ? KASHA_TP_MAX(-1.0f, KASHA_TP_MIN(1.0f, q[2] / len)) : 1.0f;
      float phi = KASHA_TP_ATAN2(q[1], q[0]);
      if (phi < 0.0f) phi += 6.283185307f;
      s = KASHA_TP_ACOS(z) * 0.318309886f;
      t = phi * 0.159154943f;
    } else if (op->type == KASHA_TEXOP_MAP_CYLINDER) {
      s = (3.141592654f + KASHA_TP_ATAN2(q[1], q[0])) * 0.159154943f;
      t = q[2];
    } else {
      s = op->f[6] + q[0] * op->f[0] + q[1] * op->f[1] + q[2] * op->f[2];
      t = op->f[7] + q[0] * op->f[3] + q[1] * op->f[4] + q[2] * op->f[5];
    }
  }
  vals[op->dst] = s;
  vals[op->dst + 1] = t;
}

/* pbrt-v4's marble: the spline parameter t = ½ + ½ sin(y + variation · FBm) of the scaled point. */
inline float marble_parameter(const KASHA_GLOBAL KTexOp* op, const float* p) {
  float x = p[0] * op->f[1], y = p[1] * op->f[1], z = p[2] * op->f[1];
  return 0.5f + 0.5f * KASHA_TP_SIN(y + op->f[2] * perlin_fbm(x, y, z, op->f[0], op->octaves));
}

/* One scalar step. */
inline void texture_step(const TexTables* tt, const KASHA_GLOBAL KTexOp* op, const TexPoint* at, float* vals) {
  int type = op->type;
  float r = 0.0f;
  if (type >= KASHA_TEXOP_MAP_UV && type <= KASHA_TEXOP_MAP_PLANE) {
    texture_map_2d(tt, op, at, vals);
    return;
  }
  if (type == KASHA_TEXOP_MAP_3D) {
    texture_point(tt->data + op->ref, at, vals + op->dst);
    return;
  }
  const float* p = vals + op->a;
  if (type == KASHA_TEXOP_CONST) {
    r = op->f[0];
  } else if (type == KASHA_TEXOP_IMAGE) {
    const KASHA_GLOBAL KTexture* t = &tt->textures[op->ref];
    int idx[4];
    float w[4];
    int n = texture_taps_st(t, vals[op->a], vals[op->b], idx, w);
    for (int k = 0; k < n; ++k)
      if (idx[k] >= 0) r += w[k] * tt->data[t->data + idx[k]];
  } else if (type == KASHA_TEXOP_CHECKER_2D) {
    r = checker_odd_st(vals[op->a], vals[op->b]) ? 1.0f : 0.0f;
  } else if (type == KASHA_TEXOP_CHECKER_3D) {
    int sum = (int)KASHA_TP_FLOOR(KASHA_TP_MAX(-1e8f, KASHA_TP_MIN(1e8f, p[0]))) +
              (int)KASHA_TP_FLOOR(KASHA_TP_MAX(-1e8f, KASHA_TP_MIN(1e8f, p[1]))) +
              (int)KASHA_TP_FLOOR(KASHA_TP_MAX(-1e8f, KASHA_TP_MIN(1e8f, p[2])));
    r = (sum & 1) ? 1.0f : 0.0f;
  } else if (type == KASHA_TEXOP_DOTS) {
    r = polka_dot(vals[op->a], vals[op->b]);
  } else if (type == KASHA_TEXOP_BILERP) {
    float s = vals[op->a], t = vals[op->b];
    r = (1.0f - s) * (1.0f - t) * op->f[0] + (1.0f - s) * t * op->f[1] + s * (1.0f - t) * op->f[2] + s * t * op->f[3];
  } else if (type == KASHA_TEXOP_FBM) {
    r = perlin_fbm(p[0], p[1], p[2], op->f[0], op->octaves);
  } else if (type == KASHA_TEXOP_WRINKLED) {
    r = perlin_turbulence(p[0], p[1], p[2], op->f[0], op->octaves);
  } else if (type == KASHA_TEXOP_WINDY) {
    float strength = perlin_fbm(0.1f * p[0], 0.1f * p[1], 0.1f * p[2], 0.5f, 3);
    r = KASHA_TP_FABS(strength) * perlin_fbm(p[0], p[1], p[2], 0.5f, 6);
  } else if (type == KASHA_TEXOP_MARBLE) {
    r = marble_parameter(op, p);
  } else if (type == KASHA_TEXOP_DIRECTION) {
    r = KASHA_TP_FABS(at->n[0] * op->f[0] + at->n[1] * op->f[1] + at->n[2] * op->f[2]);
  } else if (type == KASHA_TEXOP_MUL) {
    r = vals[op->a] * vals[op->b];
  } else if (type == KASHA_TEXOP_LERP) {
    r = (1.0f - vals[op->a]) * vals[op->b] + vals[op->a] * vals[op->c];
  } else if (type == KASHA_TEXOP_ONE_MINUS) {
    r = 1.0f - vals[op->a];
  }
  vals[op->dst] = r;
}

/* Runs a program's scalar steps into vals (KASHA_TEXTURE_SLOTS floats); the value of the last. */
inline float texture_program_run(const TexTables* tt, const KASHA_GLOBAL KTexture* t, const TexPoint* at, float* vals) {
  for (int i = 0; i < t->ops; ++i) texture_step(tt, &tt->ops[t->first_op + i], at, vals);
  return t->ops > 0 ? vals[tt->ops[t->first_op + t->ops - 1].dst] : 0.0f;
}

/* A scalar texture's value at a point: an image or checkerboard at (u, v) (texture_lookup.h), or a
 * program. */
inline float texture_scalar_at(const TexTables* tt, const KASHA_GLOBAL KTexture* t, const TexPoint* at) {
#if KASHA_TEXTURE_PROGRAMS
  if (t->type == KASHA_TEXTURE_PROGRAM) {
    float vals[KASHA_TEXTURE_SLOTS];
    return texture_program_run(tt, t, at, vals);
  }
#endif
  return texture_scalar_uv(t, tt->data, at->u, at->v);
}

#undef KASHA_TP_FLOOR
#undef KASHA_TP_SQRT
#undef KASHA_TP_ATAN2
#undef KASHA_TP_ACOS
#undef KASHA_TP_SIN
#undef KASHA_TP_FABS
#undef KASHA_TP_MIN
#undef KASHA_TP_MAX

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
