/* Georgiev's recursive partial weights dVCM, dVC, dVM (SmallVCM's names): their update at a
 * bounce and at a hit, and the densities of emission and next-event estimation they start from. */

/* A subpath's partial MIS weights after its vertex scattered it from `from` to `to` (SmallVCM's
 * SampleScattering): a delta bounce keeps them but for the cosine; any other divides by the
 * pseudo-density of the direction and carries the reverse one, with the vertex's own connection
 * and (where it merges) merge, whose part of dVC also goes to dvc_merge. Densities are about the
 * shading normal ns (nf: the front one), their turns to area about the geometric ng. False: no
 * density, the path ends. */
/* The recursion's step at a vertex that is not delta, its densities pdf (from → to) and rev
 * (to → from) known, cos_out turning the reverse one to the vertex's measure (1 in a medium). */
inline void vcm_scattered_by(float pdf, float rev, float cos_out, bool merges, float vm, float vc, float* dvcm,
                             float* dvc, float* dvm, float* dvc_merge) {
  /* dVC's part from the merge here, carried as dVC carries it (the camera's caustic merges). */
  *dvc_merge = cos_out / pdf * (*dvc_merge * rev + (merges ? vm : 0.0f));
  *dvc = cos_out / pdf * (*dvc * rev + *dvcm + (merges ? vm : 0.0f));
  *dvm = cos_out / pdf * (*dvm * rev + *dvcm * vc + (merges ? 1.0f : 0.0f));
  *dvcm = 1.0f / pdf;
}

inline bool vcm_scattered(const SceneView* s, const Surface* surf, float lambert, float3 ns, float3 nf, float3 ng,
                          float3 from, float3 to, bool delta, bool merges, float vm, float vc, float* dvcm, float* dvc,
                          float* dvm, float* dvc_merge) {
  float cos_out = fabs(dot(ng, to)); /* turns the reverse density to area: the geometric cosine */
  if (delta) {
    *dvcm = 0.0f;
    *dvc *= cos_out;
    *dvm *= cos_out;
    *dvc_merge *= cos_out;
    return true;
  }
  float pdf = vcm_pdf(s, surf, lambert, ns, nf, from, to), rev = vcm_pdf(s, surf, lambert, ns, nf, to, from);
  if (!(pdf > 0.0f)) return false;
  vcm_scattered_by(pdf, rev, cos_out, merges, vm, vc, dvcm, dvc, dvm, dvc_merge);
  return true;
}

/* The side of a surface (normal n) a direction leaves by: where a shadow ray starts off. */
inline float3 vcm_toward(float3 n, float3 d) { return dot(n, d) >= 0.0f ? n : -n; }

/* hit_no_leak for a stored light vertex, which keeps its normals rather than its hit. */
inline bool vcm_no_leak(float3 ns, float3 ng, float3 d) {
#if KASHA_SHADING_NORMALS
  return (dot(d, ns) > 0.0f) == (dot(d, ng) > 0.0f);
#else
  return true;
#endif
}

/* Next-event estimation's density, per area of the light, of the point y on emitting triangle
 * `tri` (cos_light there) from x: what sample_light_from at x truly samples — by solid angle
 * where the triangle subtends enough, else by area. A function of x and y alone, so next-event
 * estimation, a camera path hitting the lamp and a light subpath's first vertex weigh it alike,
 * and a lamp near a surface is left to the technique that samples it well, as backward's MIS does
 * (an area density there would move the weight to the camera path's hits). */
inline float vcm_direct_area(const SceneView* s, int tri, float3 x, float3 y, float cos_light) {
  float3 d = y - x;
  return light_pdf_from(s, tri, x, y, cos_light) * cos_light / dot(d, d);
}

/* Arriving at a hit at distance t, cosine cos_in: the weights turn from solid angle to area (dVC's
 * part from a merge with it). */
inline void vcm_arrived(float t, float cos_in, float* dvcm, float* dvc, float* dvm, float* dvc_merge) {
  *dvcm *= t * t / cos_in;
  *dvc /= cos_in;
  *dvm /= cos_in;
  *dvc_merge /= cos_in;
}

#if KASHA_LIGHT_SOURCES
/* A light that is not a shape, for light travelling along d from it (SmallVCM's Emit and
 * Illuminate, the pick probability left to the caller): the density of the emission technique —
 * a photon's direction (point: 1/4π, spot: uniform in its cone), or its start on the disk as wide
 * as the scene facing the direction (distant: 1/πr²; infinite: the direction's density over
 * πr²) — and, as *direct, next-event estimation's density of the same light: 1 for a delta light
 * (a point or spot's 1/d² is the caller's), the direction's density for an infinite one. */
inline float vcm_source_emission(const SceneView* s, const __global KLight* l, float3 d, float* direct) {
  *direct = 1.0f;
  if (l->type == KASHA_LIGHT_POINT) return 0.25f * KASHA_INV_PI;
#if KASHA_SPOT_LIGHTS
  if (l->type == KASHA_LIGHT_SPOT) return 1.0f / (2.0f * KASHA_PI * (1.0f - l->cos_total));
#endif
  float disk = 1.0f / (KASHA_PI * l->radius * l->radius);
#if KASHA_INFINITE_LIGHTS
  if (l->type == KASHA_LIGHT_INFINITE) {
    *direct = infinite_light_pdf(s, l, -d) / l->pick;
    return *direct * disk;
  }
#endif
  return disk;
}

/* A point or spot light: at a finite place (its photons' first hit turns to area with t²). */
inline bool vcm_source_finite(const __global KLight* l) {
  return l->type == KASHA_LIGHT_POINT || l->type == KASHA_LIGHT_SPOT;
}
#endif
