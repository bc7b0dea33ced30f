/* Sampling routines next to their densities (pbrt-v4 style). */
#ifndef KASHA_SAMPLING_H
#define KASHA_SAMPLING_H

#define KASHA_PI 3.14159265358979323846f
#define KASHA_INV_PI 0.31830988618379067154f

/* An orthonormal basis (s, t, n) around the unit vector n (Duff et al. 2017). */
inline void basis_around(float3 n, float3* s, float3* t) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float b = n.x * n.y * a;
  *s = (float3)(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  *t = (float3)(b, sign + n.y * n.y * a, -n.y);
}

#define KASHA_INV_4PI 0.07957747154594767f

/* A direction uniform on the unit sphere; density 1/(4π). */
inline float3 sample_uniform_sphere(float2 u) {
  float z = 1.0f - 2.0f * u.x, r = sqrt(fmax(0.0f, 1.0f - z * z)), c, sn = sincos(2.0f * KASHA_PI * u.y, &c);
  return (float3)(r * c, r * sn, z);
}

/* Cosine-weighted direction about n; density cos(theta)/pi per solid angle. */
inline float3 sample_cosine_hemisphere(float3 n, float u1, float u2) {
  float r = sqrt(u1), phi = 2.0f * KASHA_PI * u2;
  float3 s, t;
  basis_around(n, &s, &t);
  float z = sqrt(fmax(0.0f, 1.0f - u1));
  return normalize(r * cos(phi) * s + r * sin(phi) * t + z * n);
}
inline float cosine_hemisphere_pdf(float cos_theta) { return fmax(cos_theta, 0.0f) * KASHA_INV_PI; }

/* Uniform point on a triangle (barycentrics of v1, v2); density 1/area. */
inline float2 sample_triangle(float u1, float u2) {
  float su = sqrt(u1);
  return (float2)(su * (1.0f - u2), su * u2);
}

/* Uniform point on the unit disk (pbrt-v4's SampleUniformDiskConcentric); density 1/pi. */
inline float2 sample_disk_concentric(float2 u) {
  float2 o = 2.0f * u - 1.0f;
  if (o.x == 0.0f && o.y == 0.0f) return (float2)(0.0f, 0.0f);
  float r, theta;
  if (fabs(o.x) > fabs(o.y)) {
    r = o.x;
    theta = KASHA_PI / 4.0f * (o.y / o.x);
  } else {
    r = o.y;
    theta = KASHA_PI / 2.0f - KASHA_PI / 4.0f * (o.x / o.y);
  }
  return r * (float2)(cos(theta), sin(theta));
}

/* Mirror reflection of the direction d about the normal n. */
inline float3 reflect_dir(float3 d, float3 n) { return d - 2.0f * dot(d, n) * n; }

/* Balance heuristic for two strategies. */
inline float mis_weight(float pdf_this, float pdf_other) {
  return pdf_this > 0.0f ? pdf_this / (pdf_this + pdf_other) : 0.0f;
}

#endif
