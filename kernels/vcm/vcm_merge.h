/* Merges at a camera vertex (SmallVCM's RangeQuery and MergingCallback).
 *
 * Edge correction of merges (--edge-correction, on by default): a merge divides by the fraction of
 * its disc on surface it accepts (disc_coverage.h), measured with KASHA_VCM_COVERAGE_PROBES probes
 * once the merge has met a photon. The pattern's rotation is a hash of the vertex's position, so
 * the fraction is a function of the vertex and the radius alone; it tends to 1 with the radius
 * everywhere but on the edges themselves, so merges stay consistent. */
#ifndef KASHA_VCM_EDGE_CORRECTION
#define KASHA_VCM_EDGE_CORRECTION 0
#endif
#ifndef KASHA_VCM_COVERAGE_PROBES
#define KASHA_VCM_COVERAGE_PROBES 8
#endif

/* The disc's fraction on accepted surface at x (edge correction). */
inline float vcm_coverage(const SceneView* s, float3 x, float3 ng, float radius) {
  uint h = hash_combine(hash_combine(hash_u32(as_uint(x.x)), as_uint(x.y)), as_uint(x.z));
  float c = disc_covered(s, x, ng, radius, KASHA_GATHER_SLAB * radius, KASHA_VCM_COVERAGE_PROBES,
                         (float)h * (2.0f * KASHA_PI / 4294967296.0f));
  return c > 0.0f ? c : 1.0f; /* no probe on accepted surface: nothing to correct by */
}

#if KASHA_SCATTERING
/* A camera path's collision merging with a stored collision lv in the same medium within r, in
 * 3-D (vcm_media.h): T·f·Φ, f the phase function and the dyes, over the sphere's volume (in
 * `scale`), weighed by the collision's own η (in vc). Not edge-corrected: a per-merge division by
 * an 8-probe fraction of the sphere (sphere_coverage.h) was biased up where the sphere is cut
 * (E[1/c] > 1/E[c]: the single-scattering slab's ppm +140 % with a dye); photon mapping divides
 * its image by the fraction's mean over passes instead. The weights' merges at any other vertex sit
 * in dVC with their own η, so dVC / η here stands for SmallVCM's dVM. */
inline void vcm_merge_collision(const VcmCamera* c, const SceneView* s, const FilmView* f, const VcmVertex* cv,
                                float vc, const __global KVcmLightVertex* lv, float scale, float* rows) {
  if (lv->medium != cv->medium) return;
  const __global KMedium* m = &s->media[cv->medium];
  float3 eye = -c->w.dir, light = -load_float3(lv->arrival);
  float weight = scale * cv->sparse;
  if (KASHA_VCM_CONNECT) {
    float w_light = vc * (lv->dvcm + lv->dvc * vcm_medium_pdf(m, eye, light));
    float w_camera = vc * (c->dvcm + c->dvc * vcm_medium_pdf(m, light, eye));
    weight /= w_light + 1.0f + w_camera;
  }
  vcm_medium_camera_apply(&c->w.p, s, f, m, eye, light, vcm_vertex_power(lv), weight, rows);
}
#endif

/* A stored light vertex lv at d from the camera vertex, within r: if it merges — on the same
 * side, facing alike and near the tangent plane of the geometric surface, as photon mapping's
 * gather — it adds T·f_c·Φ weighed against the connections that sample the same path (ppm:
 * unweighted), scaled by *scale (which the first such vertex divides by the disc's coverage,
 * *covered, with edge correction). */
inline void vcm_merge_vertex(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                             const VcmVertex* cv, float vc, float radius, float3 d,
                             const __global KVcmLightVertex* lv, float* scale, float* covered, float* rows) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + lv->depth + 2)) return;
  if (!(lv->flags & KASHA_VCM_MERGEABLE)) return;
#if KASHA_SCATTERING
  /* Collisions merge with collisions, surfaces with surfaces. */
  if (cv->medium >= 0 || (lv->flags & KASHA_VCM_MEDIUM)) {
    if (cv->medium >= 0 && (lv->flags & KASHA_VCM_MEDIUM)) vcm_merge_collision(c, s, f, cv, vc, lv, *scale, rows);
    return;
  }
#endif
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  float3 ny = load_float3(lv->normal);
  /* The gather's tests about the geometric surface (a shading normal tilts off the plane the
   * photons lie in: about it the slab would cut the disc). */
  float3 ng = cv->ng;
  float3 light = -load_float3(lv->arrival);
#if KASHA_TRANSMISSION
  /* Through a transmitting surface, also the photons that arrived on its far side. */
  if (surf->share_t > 0.0f && dot(light, ng) < 0.0f) ng = -ng;
#endif
  if (dot(ny, ng) < 0.5f || fabs(dot(d, ng)) > KASHA_GATHER_SLAB * radius) return;
  if (dot(light, ng) <= 0.0f) return;
  VcmF fv = vcm_eval(s, surf, ns, cv->nf, eye, light, light, cv->eta);
  if (KASHA_VCM_EDGE_CORRECTION && *covered == 0.0f) {
    *covered = vcm_coverage(s, x, ng, radius);
    *scale /= *covered;
  }
  float weight = *scale;
  if (KASHA_VCM_CONNECT) {
    /* A light subpath that never merges (merges at the first vertex) has dVM = dVC / η; so does
     * every subpath in a scattering scene, where dVC holds each merge with its own η (a disc's
     * or a sphere's) and dVM, counting them alike, does not. */
    float dvm_light = KASHA_VCM_MERGE_EVERY && !KASHA_SCATTERING ? lv->dvm : lv->dvc * vc;
    float dvm_camera = KASHA_SCATTERING ? c->dvc * vc : c->dvm;
    float w_light = lv->dvcm * vc + dvm_light * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, light);
    float w_camera = c->dvcm * vc + dvm_camera * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, light, eye);
    weight = *scale / (w_light + 1.0f + w_camera);
  }
  vcm_camera_apply(&c->w.p, f, surf, fv, vcm_vertex_power(lv), weight, rows);
}

/* Merges at a camera vertex (SmallVCM's RangeQuery with its MergingCallback): every stored light
 * vertex within r (vcm_merge_vertex), met cell by cell of the hashed grid, each cell's run in its
 * records' order; `scale` is 1/(π r² Δλ) over a branch probability. */
inline void vcm_merge(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                      const VcmVertex* cv, float vc, float radius, float scale, const __global float* store,
                      const VcmGrid* grid, float inv_cell, uint mask, float* rows) {
  float3 x = v->h.x;
  float r2 = radius * radius;
  float covered = 0.0f; /* edge correction: the disc's fraction measured at the first photon */
  int3 lo = grid_cell(x - radius, inv_cell), hi = grid_cell(x + radius, inv_cell);
  for (int cz = lo.z; cz <= hi.z; ++cz)
    for (int cy = lo.y; cy <= hi.y; ++cy)
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        uint h = grid_hash((int3)(cx, cy, cz), mask);
        int end = grid->cell_end[h];
        for (int j = h > 0 ? grid->cell_end[h - 1] : 0; j < end; ++j) {
          /* The distance from the grid's own copy of the positions, in the cell's run; the
           * record only for a vertex within r. */
          float4 place = grid->placed[j];
          float3 y = place.xyz;
          int3 own = grid_cell(y, inv_cell);
          if (own.x != cx || own.y != cy || own.z != cz) continue;
          float3 d = y - x;
          if (!(dot(d, d) < r2)) continue;
          vcm_merge_vertex(c, s, f, v, cv, vc, radius, d, vcm_vertex(store, as_int(place.w)), &scale, &covered,
                           rows);
        }
      }
}
