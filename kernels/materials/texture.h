/* Textures at a hit (docs/textures.md): a material's reflectance texture multiplies its passive
 * reflectance ρ(λ) bin by bin, its fluorescence texture scales its excitation a(λ) (an ink's
 * concentration), its roughness textures set its GGX alpha there (roughness_at). The textured
 * spectra are computed into the work item's scratch spectra, so the rest of the kernels read them
 * through the Surface's pointers as any other spectrum.
 * Lookups follow pbrt-v4: (s, t) = (u·uscale + udelta, v·vscale + vdelta); an image's t runs up
 * from its bottom row; bilinear filtering between texel centres (or the nearest texel); wrap by
 * repeating, clamping to the edge, black outside [0, 1)², or mirrored as pbrt-v4's octahedral
 * sphere. A checkerboard is even where
 * ⌊s⌋ + ⌊t⌋ is even. A spectral image blends its four texels' spectra, not their colours. */
#ifndef KASHA_TEXTURE_H
#define KASHA_TEXTURE_H

#include "geometry/hit_point.h"
#include "materials/rgb_spectrum.h"
#include "materials/surface.h"
#include "shared/texture_lookup.h"
#include "shared/texture_program.h"

#ifndef KASHA_EMISSION_TEXTURES
#define KASHA_EMISSION_TEXTURES 0 /* some emitter's radiance is multiplied by a texture */
#endif
#ifndef KASHA_ROUGHNESS_TEXTURES
#define KASHA_ROUGHNESS_TEXTURES 0 /* some rough material's roughness is a texture's value */
#endif
#ifndef KASHA_SCRATCH_TEXTURES
#define KASHA_SCRATCH_TEXTURES 0 /* where the textured spectra start in the scratch */
#endif

#if KASHA_TEXTURES
/* The texture coordinates at barycentrics (b1, b2) of leaf triangle tri. */
inline float2 triangle_uv(const SceneView* s, int tri, float b1, float b2) {
  const __global float* t = s->texcoords[tri].uv;
  float b0 = 1.0f - b1 - b2;
  return (float2)(b0 * t[0] + b1 * t[2] + b2 * t[4], b0 * t[1] + b1 * t[3] + b2 * t[5]);
}

inline float2 hit_uv(const SceneView* s, const HitPoint* h) { return triangle_uv(s, h->tri, h->b.x, h->b.y); }

inline float2 texture_st(const __global KTexture* t, float2 uv) {
  return (float2)(uv.x * t->uscale + t->udelta, uv.y * t->vscale + t->vdelta);
}

/* The texels an image lookup at st blends and their weights (shared/texture_lookup.h). */
inline int texture_taps(const __global KTexture* t, float2 st, int* idx, float* w) {
  return texture_taps_st(t, st.x, st.y, idx, w);
}

inline bool checker_odd(float2 st) { return checker_odd_st(st.x, st.y); }

/* A scalar texture's value at uv. */
inline float texture_scalar(const SceneView* s, const __global KTexture* t, float2 uv) {
  return texture_scalar_uv(t, s->spectra, uv.x, uv.y);
}

/* T(uv) bin by bin into out: a checkerboard's spectrum or an image's texel blend. */
inline void texture_factor(const SceneView* s, const __global KTexture* t, float2 uv, __global float* out) {
  float2 st = texture_st(t, uv);
  if (t->type == KASHA_TEXTURE_CHECKERBOARD) {
    const __global float* v = s->spectra + (checker_odd(st) ? t->odd : t->even);
    for (int i = 0; i < KASHA_BINS; ++i) out[i] = v[i];
    return;
  }
  int idx[4];
  float w[4];
  int n = texture_taps(t, st, idx, w);
  for (int i = 0; i < KASHA_BINS; ++i) {
    float nm = s->spectra[t->lambda + i], v = 0.0f;
    for (int k = 0; k < n; ++k)
      if (idx[k] >= 0) v += w[k] * rgb_sigmoid(s->spectra + t->data + 4 * idx[k], nm);
    out[i] = v;
  }
}

#if KASHA_TEXTURE_PROGRAMS
/* T at the point into out: a spectral program's terms summed bin by bin (each a slot's value times
 * a constant spectrum or an image's texel blend), clamped to [0, 1] as pbrt-v4 clamps a
 * reflectance. */
inline void texture_program_factor(const SceneView* s, const __global KTexture* t, const TexPoint* at,
                                   __global float* out) {
  TexTables tt = scene_texture_tables(s);
  float vals[KASHA_TEXTURE_SLOTS];
  texture_program_run(&tt, t, at, vals);
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = 0.0f;
  for (int k = 0; k < t->terms; ++k) {
    const __global KTexOp* op = &s->tex_ops[t->first_term + k];
    float w = vals[op->a];
    if (w == 0.0f) continue;
    if (op->type == KASHA_TEXOP_TERM_SPECTRUM) {
      const __global float* v = s->spectra + op->ref;
      for (int i = 0; i < KASHA_BINS; ++i) out[i] += w * v[i];
      continue;
    }
    const __global KTexture* image = &s->textures[op->ref];
    int idx[4];
    float tw[4];
    int n = texture_taps_st(image, vals[op->b], vals[op->c], idx, tw);
    for (int i = 0; i < KASHA_BINS; ++i) {
      float nm = s->spectra[image->lambda + i], v = 0.0f;
      for (int j = 0; j < n; ++j)
        if (idx[j] >= 0) v += tw[j] * rgb_sigmoid(s->spectra + image->data + 4 * idx[j], nm);
      out[i] += w * v;
    }
  }
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = clamp(out[i], 0.0f, 1.0f);
}
#endif

/* Where a hit's textures are looked up, built once a hit: its (u, v), and with texture programs
 * its point and normal too (shared/texture_program.h); without them nothing reads those. */
inline TexPoint hit_tex_point(const SceneView* s, const HitPoint* h) {
#if KASHA_TEXTURE_PROGRAMS
  return triangle_tex_point(&s->tris[h->tri], &s->texcoords[h->tri], h->b.x, h->b.y);
#else
  TexPoint at;
  float2 uv = hit_uv(s, h);
  at.u = uv.x;
  at.v = uv.y;
  return at;
#endif
}

/* A spectral texture's factor T bin by bin at the point into out: a program where the texture is
 * one, else the lookup at (u, v). */
inline void texture_factor_at(const SceneView* s, const __global KTexture* t, const TexPoint* at,
                              __global float* out) {
#if KASHA_TEXTURE_PROGRAMS
  if (t->type == KASHA_TEXTURE_PROGRAM) {
    texture_program_factor(s, t, at, out);
    return;
  }
#endif
  texture_factor(s, t, (float2)(at->u, at->v), out);
}

/* out = y ∘ T, T a factor texture_factor_at wrote (out may be T itself). */
inline void texture_apply(const __global float* y, const __global float* factor, __global float* out) {
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = y[i] * factor[i];
}

#if KASHA_EMISSION_TEXTURES
/* What an emission texture multiplies the emitter's radiance by at barycentrics (b1, b2) of
 * leaf triangle tri (1 without one). */
inline float emission_factor(const SceneView* s, int tri, float b1, float b2) {
  int t = s->texcoords[tri].emission_texture;
  return t < 0 ? 1.0f : texture_scalar(s, &s->textures[t], triangle_uv(s, tri, b1, b2));
}
#endif

#if KASHA_ROUGHNESS_TEXTURES
/* The GGX alpha at the point of a material whose roughness is textured: each textured axis's value
 * there, clamped to [0, 1] and remapped as a constant is (pbrt-v4's RoughnessToAlpha: sqrt). The
 * point is smooth or rough by this alpha alone (surface_rough), so every integrator decides alike;
 * where it is rough, both axes stay at least 1e-4 as pbrt-v4's TrowbridgeReitzDistribution keeps
 * them (D would divide by a zero alpha). */
inline void roughness_at(const SceneView* s, const TexPoint* at, Surface* surf) {
  const __global KMaterial* m = surf->m;
  if (m->alpha_texture[0] < 0 && m->alpha_texture[1] < 0) return;
  TexTables tt = scene_texture_tables(s);
  float a[2] = {m->alpha[0], m->alpha[1]};
  for (int k = 0; k < 2; ++k) {
    int t = m->alpha_texture[k];
    if (t < 0) continue;
    if (k == 1 && t == m->alpha_texture[0]) {
      a[1] = a[0]; /* isotropic: one lookup */
      continue;
    }
    float r = clamp(texture_scalar_at(&tt, &s->textures[t], at), 0.0f, 1.0f);
    a[k] = m->remap_alpha ? sqrt(r) : r;
  }
  if (fmax(a[0], a[1]) >= KASHA_SMOOTH_ALPHA) {
    a[0] = fmax(a[0], 1e-4f);
    a[1] = fmax(a[1], 1e-4f);
  }
  surf->alpha.ax = a[0];
  surf->alpha.ay = a[1];
}
#endif

/* Whether some texture of the material applies at its points. */
inline bool material_textured(const __global KMaterial* m) {
#if KASHA_ROUGHNESS_TEXTURES
  if (m->alpha_texture[0] >= 0 || m->alpha_texture[1] >= 0) return true;
#endif
  return m->reflectance_texture >= 0 || m->fluorescence_texture >= 0;
}

/* The hit's surface with its material's textures applied, all looked up at one TexPoint. */
inline void load_textured_surface(const SceneView* s, const HitPoint* h, Surface* surf) {
  load_surface(s, h->material, surf);
  const __global KMaterial* m = surf->m;
  if (!material_textured(m)) return;
  TexPoint at = hit_tex_point(s, h);
#if KASHA_ROUGHNESS_TEXTURES
  roughness_at(s, &at, surf);
#endif
  __global float* slot = s->scratch + KASHA_SCRATCH_TEXTURES;
  if (m->reflectance_texture >= 0) {
    texture_factor_at(s, &s->textures[m->reflectance_texture], &at, slot);
#if KASHA_TRANSMISSION
    /* The reflectance texture colours the transmittance alike (docs/materials.md): one factor. */
    if (surf->share_t > 0.0f) {
      texture_apply(surf->tau, slot, slot + 2 * KASHA_BINS);
      surf->tau = slot + 2 * KASHA_BINS;
    }
#endif
    texture_apply(surf->rho, slot, slot);
    surf->rho = slot;
  }
#if KASHA_FLUORESCENCE
  if (m->fluorescence_texture >= 0) {
    TexTables tt = scene_texture_tables(s);
    float k = clamp(texture_scalar_at(&tt, &s->textures[m->fluorescence_texture], &at), 0.0f, 1.0f);
    __global float* a = slot + KASHA_BINS;
    for (int i = 0; i < KASHA_BINS; ++i) a[i] = surf->a[i] * k;
    surf->a = a;
    surf->a_sum *= k;
    /* No ink here: the material's passive part alone, as if it did not fluoresce. */
    if (!(k > 0.0f)) surf->fluorescent = false;
  }
#endif
}
#else
inline void load_textured_surface(const SceneView* s, const HitPoint* h, Surface* surf) { load_surface(s, h->material, surf); }
#endif

#endif
