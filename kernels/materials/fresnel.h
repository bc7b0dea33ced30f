/* Fresnel reflectance of smooth interfaces, unpolarized light (pbrt-v4's FrDielectric and
 * FrComplex, docs/materials.md#fresnel): a dielectric of relative index eta, and a conductor of
 * complex relative index eta + i k, as functions of the cosine of the angle of incidence. */
#ifndef KASHA_FRESNEL_H
#define KASHA_FRESNEL_H

/* cos_i > 0 on the side the light arrives from; eta: index of the far side over the near one.
 * 1 under total internal reflection. */
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = clamp(cos_i, 0.0f, 1.0f);
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = sqrt(1.0f - sin2_t);
  float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

/* A thin dielectric sheet's reflectance (pbrt-v4's ThinDielectricBxDF): R' = R + T²R / (1 − R²)
 * with R = F(cos_i, eta) and T = 1 − R, every round trip between its faces summed; the rest passes
 * straight through. */
inline float thin_dielectric_reflectance(float cos_i, float eta) {
  float r = fresnel_dielectric(fabs(cos_i), eta);
  if (r < 1.0f) r += (1.0f - r) * (1.0f - r) * r / (1.0f - r * r);
  return r;
}

/* The direction d refracted through the interface with normal n on d's side (dot(d, n) < 0,
 * cos_i = -dot(d, n)), eta as above; the caller has ruled out total internal reflection. */
inline float3 refract_dir(float3 d, float3 n, float cos_i, float eta) {
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
  return normalize(d / eta + (cos_i / eta - cos_t) * n);
}

/* Complex numbers as (re, im). */
inline float2 c_mul(float2 a, float2 b) { return (float2)(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
inline float2 c_div(float2 a, float2 b) {
  float d = b.x * b.x + b.y * b.y;
  return (float2)(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / d;
}
inline float c_norm(float2 a) { return a.x * a.x + a.y * a.y; }
/* The principal square root. */
inline float2 c_sqrt(float2 z) {
  float r = sqrt(sqrt(c_norm(z)));
  if (r == 0.0f) return (float2)(0.0f);
  float half_arg = 0.5f * atan2(z.y, z.x);
  return (float2)(r * cos(half_arg), r * sin(half_arg));
}

inline float fresnel_conductor(float cos_i, float eta, float k) {
  cos_i = clamp(cos_i, 0.0f, 1.0f);
  float2 n = (float2)(eta, k);
  float2 sin2_t = c_div((float2)(1.0f - cos_i * cos_i, 0.0f), c_mul(n, n));
  float2 cos_t = c_sqrt((float2)(1.0f, 0.0f) - sin2_t);
  float2 nc = n * cos_i, nct = c_mul(n, cos_t);
  float r_parallel = c_norm(c_div(nc - cos_t, nc + cos_t));
  float r_perpendicular = c_norm(c_div((float2)(cos_i, 0.0f) - nct, (float2)(cos_i, 0.0f) + nct));
  return 0.5f * (r_parallel + r_perpendicular);
}

#endif
