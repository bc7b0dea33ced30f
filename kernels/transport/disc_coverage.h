/* The fraction of a gather disc that lies on surface a gather accepts: photon mapping's edge
 * correction (photon_gather.cl, disc_coverage) and vcm's merges (vcm.cl, vcm_merge).
 * Near an edge a disc hangs over it; the photons there are rejected by the normal test while the
 * density estimate divides by the whole disc, so the image darkens towards edges and corners.
 * `probes` short rays along the normal through the gather's slab, at equal-area radii on a
 * golden-angle pattern rotated by `rotation`, find the fraction on surface whose normal is within
 * 60° of n (the gather's own test). Needs the scene view (scene_view.h, bvh_traversal.h). */
#ifndef KASHA_DISC_COVERAGE_H
#define KASHA_DISC_COVERAGE_H

inline float disc_covered(const SceneView* s, float3 x, float3 n, float r, float slab, int probes,
                          float rotation) {
  /* A tangent basis (t1, t2) around n (Duff et al. 2017). */
  float sign = n.z >= 0.0f ? 1.0f : -1.0f, a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  float3 t1 = (float3)(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  float3 t2 = (float3)(b, sign + n.y * n.y * a, -n.y);
  int covered = 0;
  for (int j = 0; j < probes; ++j) {
    float rho = r * sqrt((j + 0.5f) / probes);
    float phi = rotation + 2.39996323f * j; /* the golden angle: probes spread over the disc */
    float3 org = x + rho * (cos(phi) * t1 + sin(phi) * t2) + slab * n;
    float t, u, v;
    ++s->rays->closest;
    AlphaTables alpha = scene_alpha(s);
    BvhTables bvh = scene_bvh(s);
    int inst;
    int hit = bvh_closest(&bvh, &alpha, org, -n, 0.0f, 2.0f * slab, &t, &u, &v, &inst);
    if (hit < 0) continue;
    const __global KTriangle* tri = &s->tris[hit];
    float3 v0 = load_float3(tri->v0);
    float3 g = normalize(cross(load_float3(tri->v1) - v0, load_float3(tri->v2) - v0));
#if KASHA_INSTANCES
    g = normalize(affine_normal(s->instances[inst].object_from_world, g));
#endif
    /* The normal on the side the probe arrives from, n's side, is |g·n| from n. */
    if (fabs(dot(g, n)) > 0.5f) ++covered;
  }
  return (float)covered / probes;
}

#endif
