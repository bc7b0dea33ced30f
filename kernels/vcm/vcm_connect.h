/* Connections of a camera vertex to its light subpath's stored vertices (SmallVCM's
 * ConnectVertices). */
/* A camera vertex connects to at most this many vertices of its light subpath: all of them in
 * ordinary scenes (a few a subpath), an unbiased thinning of a long one (vcm_connect). */
#define KASHA_VCM_CONNECTIONS 8

/* The surface of a stored light vertex as the light subpath met it (textures at its barycentrics,
 * a coat for its arrival), its spectra in the work item's own scratch `room` so that the camera
 * vertex's stay. *ns: the shading normal on the light's side, *nf the front one, *ng the
 * geometric one on the light's side. */
inline void vcm_light_surface(const SceneView* s, const __global KVcmLightVertex* y, __global float* room,
                              Surface* sy, float3* ns, float3* nf, float3* ng) {
  HitPoint h;
  h.tri = y->triangle;
#if KASHA_INSTANCES
  h.instance = y->instance;
#endif
  const __global KTriangle* t = &s->tris[h.tri];
  /* The material the light subpath resolved there: the same point, the same choice. */
  h.material = resolve_material(s, t->material, load_float3(y->position), h.tri,
                                (float2)(y->barycentrics[0], y->barycentrics[1]));
  *ns = load_float3(y->shading);
  *ng = load_float3(y->normal);
  *nf = (y->flags & KASHA_VCM_FRONT) ? *ns : -*ns;
#if KASHA_TEXTURES || KASHA_MIX || KASHA_NORMAL_MAPS
  h.b = (float2)(y->barycentrics[0], y->barycentrics[1]);
#endif
#if KASHA_COATED
  h.cos_in = fabs(dot(*ng, load_float3(y->arrival))); /* ng is ±the front normal */
#endif
  SceneView own = *s;
  own.scratch = room;
  load_surface_at(&own, &h, sy);
}

/* Connections of a camera vertex to the stored vertices of its light subpath, the last stored
 * at record `last` (SmallVCM's ConnectVertices): T·f_c·G·f_l·Φ, Φ per light subpath (paths/Δλ
 * undoes the photon's 1/paths and bin width). A subpath of n > KASHA_VCM_CONNECTIONS vertices
 * (a furnace of albedo 0.999 stores a thousand) is thinned: with s = ⌈n / KASHA_VCM_CONNECTIONS⌉
 * only the vertices whose ordinal is o mod s, o uniform in [0, s) from `u`, connect, each
 * weighed s — every vertex with probability 1/s, so the sum is unbiased and a path of n camera
 * vertices costs O(n) shadow rays, not O(n²). `out` is the work item's spectra (VCM_SPECTRA):
 * f_l·Φ, then the light vertex's surface. */
inline void vcm_connect(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                        const VcmVertex* cv, float vm, float paths, const __global float* store, int last, uint u,
                        __global float* out, float* rows) {
  if (last < 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  int n = vcm_vertex(store, last)->ordinal + 1;
  int stride = (n + KASHA_VCM_CONNECTIONS - 1) / KASHA_VCM_CONNECTIONS;
  int offset = (int)(u % (uint)stride);
  for (int slot = last; slot >= 0;) {
    const __global KVcmLightVertex* lv = vcm_vertex(store, slot);
    slot = lv->previous;
    if (lv->ordinal % stride != offset) continue;
    if (!VCM_LENGTH_COUNTS(c->w.depth + lv->depth + 3)) continue;
    float3 y = load_float3(lv->position);
    float3 d = y - x;
    float dist2 = dot(d, d), dist = sqrt(dist2);
    float3 dir = d / dist;
    VcmF fc = vcm_eval(s, surf, ns, cv->nf, eye, dir, dir, cv->eta);
    if (!vcm_f_nonzero(&fc)) continue;
    if (!hit_no_leak(&v->h, dir)) continue;
    Surface sy;
    float3 ny, nfy, ngy;
    vcm_light_surface(s, lv, out + KASHA_BINS, &sy, &ny, &nfy, &ngy);
    if (!vcm_no_leak(ny, ngy, -dir)) continue;
    float3 light = -load_float3(lv->arrival);
    VcmF fl = vcm_eval(s, &sy, ny, nfy, -dir, light, -dir, vcm_light_eta(&sy));
    if (!vcm_f_nonzero(&fl)) continue;
    /* The camera side's radiance takes the shading cosine; the turns to area, the geometric. */
    float cos_s = fabs(dot(ns, dir)), cos_c = fabs(dot(cv->ng, dir)), cos_y = fabs(dot(ngy, dir));
    float lambert_y = vcm_lambert_mean(&sy);
    bool merges_y = KASHA_VCM_MERGE_EVERY && (lv->flags & KASHA_VCM_MERGEABLE); /* else behind the camera's merging vertex */
    float w_light = vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, dir) * cos_y / dist2 *
                    ((merges_y ? vm : 0.0f) + lv->dvcm + lv->dvc * vcm_pdf(s, &sy, lambert_y, ny, nfy, -dir, light));
    float w_camera = vcm_pdf(s, &sy, lambert_y, ny, nfy, light, -dir) * cos_c / dist2 *
                     ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm : 0.0f) + c->dvcm +
                      vcm_camera_dvc(c) * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, dir, eye));
    float weight = 1.0f / (w_light + 1.0f + w_camera);
    if (!(weight > 0.0f)) continue;
#if KASHA_MEDIA
    const __global float* tr;
    if (!segment_clear(s, x, vcm_toward(cv->ng, dir), v->h.eps, dir, dist, lv->eps / cos_y,
                       medium_after(s, v->h.tri, v->h.n, dir, c->w.medium), &tr))
      continue;
    vcm_light_apply(&sy, fl, vcm_vertex_power(lv), out);
    if (tr)
      for (int i = 0; i < KASHA_BINS; ++i) out[i] *= tr[i];
#else
    if (segment_occluded(s, x, vcm_toward(cv->ng, dir), v->h.eps, dir, dist, lv->eps / cos_y)) continue;
    vcm_light_apply(&sy, fl, vcm_vertex_power(lv), out);
#endif
    vcm_camera_apply(&c->w.p, f, surf, fc, out, stride * weight * cos_s * cos_y / dist2 * paths / s->bin_nm, rows);
  }
}
