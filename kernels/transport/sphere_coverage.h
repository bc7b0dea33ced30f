/* The fraction of a gather sphere that lies in the medium of its centre: the edge correction of
 * photon mapping's gathers in media (photon_gather.cl, disc_coverage), the volume's counterpart of
 * disc_coverage.h. Near a medium's boundary the sphere reaches out of it; no photon of the medium
 * lies out there while the density estimate divides by the whole sphere, so the medium darkens
 * towards its boundary. `probes` points in the sphere — radii from the radical inverse, directions
 * on a spherical Fibonacci spiral, turned by `rotation` — count where the segment from the centre
 * meets no surface (any surface bounds the region a gather reaches). Needs the scene view
 * (scene_view.h, bvh_traversal.h). */
#ifndef KASHA_SPHERE_COVERAGE_H
#define KASHA_SPHERE_COVERAGE_H

/* j's bits reversed, as a fraction in [0, 1) (van der Corput). */
inline float radical_inverse_2(uint j) {
  j = (j << 16) | (j >> 16);
  j = ((j & 0x00ff00ffu) << 8) | ((j & 0xff00ff00u) >> 8);
  j = ((j & 0x0f0f0f0fu) << 4) | ((j & 0xf0f0f0f0u) >> 4);
  j = ((j & 0x33333333u) << 2) | ((j & 0xccccccccu) >> 2);
  j = ((j & 0x55555555u) << 1) | ((j & 0xaaaaaaaau) >> 1);
  return (float)j * 0x1p-32f;
}

inline float sphere_covered(const SceneView* s, float3 x, float r, int probes, float rotation) {
  AlphaTables alpha = scene_alpha(s);
  BvhTables bvh = scene_bvh(s);
  float shift = rotation * 0.15915494f; /* the rotation as a fraction of a turn */
  int covered = 0;
  for (int j = 0; j < probes; ++j) {
    /* Uniform in the ball: r ∛u from a radical inverse, the direction on the spiral. */
    float u = radical_inverse_2((uint)j) + shift;
    float rho = r * cbrt(u - floor(u));
    float z = 1.0f - 2.0f * ((float)j + 0.5f) / (float)probes, ring = sqrt(fmax(0.0f, 1.0f - z * z));
    float phi = rotation + 2.39996323f * (float)j; /* the golden angle */
    float3 d = (float3)(ring * cos(phi), ring * sin(phi), z);
    ++s->rays->shadow;
    if (!(rho > 0.0f) || !bvh_occluded(&bvh, &alpha, x, d, 0.0f, rho)) ++covered;
  }
  return (float)covered / (float)probes;
}

#endif
