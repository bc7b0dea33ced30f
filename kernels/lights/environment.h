/* An infinite light with an environment image (docs/lights.md#environment-images): each texel
 * holds an RGB colour as pbrt-v4's RGBIlluminantSpectrum makes it, scale · S(c0 λ² + c1 λ + c2)
 * times the light's row of emitter_radiance (D65 normalised to luminance 1, times the light's
 * scale), S the sigmoid; the texel a direction falls in gives its radiance (no filtering, so the
 * radiance is exactly what the sampling distribution was built from). Directions map to the
 * image by latitude-longitude (+z the top row, φ from +x towards +y) or by Clarberg's equal-area
 * square (pbrt-v4's), in the light's frame (to_light, any invertible map, directions normalised
 * after it as pbrt-v4 does; a general map's solid-angle Jacobian enters the densities, which
 * pbrt-v4 leaves out). Sampling is piecewise constant over the
 * texels: a marginal CDF over rows, then a conditional CDF over the row's texels, built on the
 * host from each texel's mean RGB (times sin θ for latitude-longitude). */
#ifndef KASHA_ENVIRONMENT_H
#define KASHA_ENVIRONMENT_H

#include "materials/rgb_spectrum.h"
#include "sampling/sampling.h"
#include "geometry/scene_view.h"
#include "geometry/equal_area.h"

#ifndef KASHA_ENVIRONMENT
#define KASHA_ENVIRONMENT 0
#endif

#if KASHA_ENVIRONMENT

/* The image frame's direction for the world direction w; a general map (not a rotation or a
 * mirror) is normalised after it, and *jacobian is its solid-angle Jacobian
 * |det M| / |M w|³ (1 for an orthogonal M). */
inline float3 env_to_light(const __global KLight* l, float3 w, float* jacobian) {
  const __global float* m = l->to_light;
  float3 d = (float3)(m[0] * w.x + m[1] * w.y + m[2] * w.z, m[3] * w.x + m[4] * w.y + m[5] * w.z,
                      m[6] * w.x + m[7] * w.y + m[8] * w.z);
  *jacobian = 1.0f;
  if (!l->general) return d;
  float3 r0 = (float3)(m[0], m[1], m[2]), r1 = (float3)(m[3], m[4], m[5]), r2 = (float3)(m[6], m[7], m[8]);
  float len = length(d);
  *jacobian = fabs(dot(r0, cross(r1, r2))) / (len * len * len);
  return d / len;
}

/* The world direction for the image frame's unit direction d: M⁻¹ d normalised (the transpose
 * for an orthogonal M); *jacobian as env_to_light's at that world direction. */
inline float3 env_to_world(const __global KLight* l, float3 d, float* jacobian) {
  const __global float* m = l->to_light;
  *jacobian = 1.0f;
  if (!l->general)
    return (float3)(m[0] * d.x + m[3] * d.y + m[6] * d.z, m[1] * d.x + m[4] * d.y + m[7] * d.z,
                    m[2] * d.x + m[5] * d.y + m[8] * d.z);
  float3 r0 = (float3)(m[0], m[1], m[2]), r1 = (float3)(m[3], m[4], m[5]), r2 = (float3)(m[6], m[7], m[8]);
  float det = dot(r0, cross(r1, r2));
  /* M⁻¹'s columns are the rows' cross products over det. */
  float3 u = (cross(r1, r2) * d.x + cross(r2, r0) * d.y + cross(r0, r1) * d.z) / det;
  float len = length(u);
  *jacobian = fabs(det) * len * len * len;
  return u / len;
}

/* The image position (u, v) in [0, 1)² of the world direction w, and the Jacobian factor that
 * turns a density over (u, v) into one over world solid angle (1 / (2π² sin θ), or 1 / (4π),
 * times the map's own). */
inline float2 env_uv(const __global KLight* l, float3 w, float* to_solid_angle) {
  float map_jacobian;
  float3 d = env_to_light(l, w, &map_jacobian);
  if (l->mapping == KASHA_MAPPING_EQUAL_AREA) {
    *to_solid_angle = 0.25f * KASHA_INV_PI * map_jacobian;
    return equal_area_to_square(d);
  }
  /* sin θ from x and y: near the poles 1 − cos² θ loses it to rounding. */
  float cos_t = clamp(d.z, -1.0f, 1.0f), sin_t = length((float2)(d.x, d.y));
  float phi = atan2(d.y, d.x);
  if (phi < 0.0f) phi += 2.0f * KASHA_PI;
  *to_solid_angle = sin_t > 0.0f ? map_jacobian / (2.0f * KASHA_PI * KASHA_PI * sin_t) : 0.0f;
  return (float2)(phi * (0.5f * KASHA_INV_PI), atan2(sin_t, cos_t) * KASHA_INV_PI);
}

inline float3 env_direction(const __global KLight* l, float2 uv, float* to_solid_angle) {
  float3 d;
  if (l->mapping == KASHA_MAPPING_EQUAL_AREA) {
    d = equal_area_to_sphere(uv);
    *to_solid_angle = 0.25f * KASHA_INV_PI;
  } else {
    float theta = uv.y * KASHA_PI, phi = uv.x * 2.0f * KASHA_PI, sin_t, cos_t = cos(theta), c, sn;
    sin_t = sin(theta);
    sn = sincos(phi, &c);
    d = (float3)(sin_t * c, sin_t * sn, cos_t);
    *to_solid_angle = sin_t > 0.0f ? 1.0f / (2.0f * KASHA_PI * KASHA_PI * sin_t) : 0.0f;
  }
  float map_jacobian;
  float3 w = env_to_world(l, d, &map_jacobian);
  *to_solid_angle *= map_jacobian;
  return w;
}

inline int env_texel(const __global KLight* l, float2 uv) {
  int x = clamp((int)(uv.x * (float)l->width), 0, l->width - 1);
  int y = clamp((int)(uv.y * (float)l->height), 0, l->height - 1);
  return y * l->width + x;
}

/* The probability of texel t under the sampling distribution, times the texel count: the
 * density over (u, v) in [0, 1)². */
inline float env_texel_density(const SceneView* s, const __global KLight* l, int t) {
  const __global float* marginal = s->spectra + l->distribution;
  const __global float* conditional = marginal + l->height + 1;
  int y = t / l->width, x = t - y * l->width;
  const __global float* row = conditional + y * (l->width + 1);
  return (marginal[y + 1] - marginal[y]) * (row[x + 1] - row[x]) * (float)(l->width * l->height);
}

/* The first of n + 1 CDF values (cdf[0] = 0, cdf[n] = 1) whose step holds u: the cell k with
 * cdf[k] <= u < cdf[k + 1], skipping empty cells. */
inline int cdf_find(const __global float* cdf, int n, float u) {
  int lo = 0, hi = n - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (cdf[mid + 1] > u) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

/* A direction drawn from the image's distribution: its texel, and its solid-angle density (0
 * where the mapping's Jacobian vanishes). */
inline float3 env_sample(const SceneView* s, const __global KLight* l, float2 u, int* texel, float* pdf) {
  const __global float* marginal = s->spectra + l->distribution;
  const __global float* conditional = marginal + l->height + 1;
  int y = cdf_find(marginal, l->height, u.x);
  float dy = marginal[y + 1] - marginal[y];
  float fy = dy > 0.0f ? clamp((u.x - marginal[y]) / dy, 0.0f, 0.99999994f) : 0.5f;
  const __global float* row = conditional + y * (l->width + 1);
  int x = cdf_find(row, l->width, u.y);
  float dx = row[x + 1] - row[x];
  float fx = dx > 0.0f ? clamp((u.y - row[x]) / dx, 0.0f, 0.99999994f) : 0.5f;
  float2 uv = (float2)(((float)x + fx) / (float)l->width, ((float)y + fy) / (float)l->height);
  float jacobian;
  float3 w = env_direction(l, uv, &jacobian);
  *texel = y * l->width + x;
  *pdf = dy * dx * (float)(l->width * l->height) * jacobian;
  return w;
}

/* The solid-angle density with which env_sample draws the world direction w. */
inline float env_pdf(const SceneView* s, const __global KLight* l, float3 w) {
  float jacobian;
  float2 uv = env_uv(l, w, &jacobian);
  return env_texel_density(s, l, env_texel(l, uv)) * jacobian;
}

/* The radiance of texel t in bin i. */
inline float env_radiance(const SceneView* s, const __global KLight* l, int t, int i) {
  const __global float* c = s->spectra + l->image + 4 * t;
  return c[3] * rgb_sigmoid(c, s->spectra[l->lambda + i]) * emitter_spectrum(s, l->spectrum)[i];
}

/* Texel t's spectrum into out (the work item's scratch spectrum): what the path weight is
 * applied to, in global memory like every other spectrum. */
inline const __global float* env_spectrum(const SceneView* s, const __global KLight* l, int t, __global float* out) {
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = env_radiance(s, l, t, i);
  return out;
}

#endif
#endif
