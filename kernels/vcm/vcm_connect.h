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

#if KASHA_SCATTERING
/* The medium of a camera vertex that is a collision, else null. */
inline const __global KMedium* vcm_collision_medium(const SceneView* s, const VcmVertex* cv) {
  return cv->medium >= 0 ? &s->media[cv->medium] : 0;
}
#endif

/* One end of a connection as the weights and the contribution see it: f there (a surface's parts,
 * or a collision's phase function and dyes), the densities of leaving it along the connection
 * and back, the cosine that turns the other end's density to it (1 at a collision: volume) and
 * the radiance's shading cosine there, and σ̄ (1 at a surface). */
typedef struct {
  VcmF f;
  float pdf_out, pdf_back, cos_g, cos_s, sigma;
} VcmEnd;

/* The camera vertex's end of a connection along dir (eye: towards the camera). False: f is 0 or
 * the direction leaks through the surface. */
inline bool vcm_camera_end(const SceneView* s, const CameraVertex* v, const VcmVertex* cv, float3 eye, float3 dir,
                           VcmEnd* e) {
#if KASHA_SCATTERING
  const __global KMedium* m = vcm_collision_medium(s, cv);
  if (m) {
    e->pdf_out = e->pdf_back = vcm_medium_pdf(m, eye, dir);
    e->cos_g = e->cos_s = 1.0f;
    e->sigma = m->sigma_mean;
    return true;
  }
#endif
  e->f = vcm_eval(s, &v->surf, cv->ns, cv->nf, eye, dir, dir, cv->eta);
  if (!vcm_f_nonzero(&e->f) || !hit_no_leak(&v->h, dir)) return false;
  e->pdf_out = vcm_pdf(s, &v->surf, cv->lambert, cv->ns, cv->nf, eye, dir);
  e->pdf_back = vcm_pdf(s, &v->surf, cv->lambert, cv->ns, cv->nf, dir, eye);
  e->cos_s = fabs(dot(cv->ns, dir));
  e->cos_g = fabs(dot(cv->ng, dir));
  e->sigma = 1.0f;
  return true;
}

/* The light vertex's end of a connection along -dir (the light arrived from `light`), its surface
 * (a surface vertex) in *sy with its spectra in `room`. False: f is 0 or it leaks. */
inline bool vcm_light_end(const SceneView* s, const __global KVcmLightVertex* lv, float3 dir, __global float* room,
                          Surface* sy, VcmEnd* e) {
  float3 light = -load_float3(lv->arrival);
#if KASHA_SCATTERING
  if (lv->flags & KASHA_VCM_MEDIUM) {
    const __global KMedium* m = &s->media[lv->medium];
    e->pdf_out = e->pdf_back = vcm_medium_pdf(m, light, -dir);
    e->cos_g = e->cos_s = 1.0f;
    e->sigma = m->sigma_mean;
    return true;
  }
#endif
  float3 ny, nfy, ngy;
  vcm_light_surface(s, lv, room, sy, &ny, &nfy, &ngy);
  if (!vcm_no_leak(ny, ngy, -dir)) return false;
  e->f = vcm_eval(s, sy, ny, nfy, -dir, light, -dir, vcm_light_eta(sy));
  if (!vcm_f_nonzero(&e->f)) return false;
  float lambert_y = vcm_lambert_mean(sy);
  e->pdf_out = vcm_pdf(s, sy, lambert_y, ny, nfy, light, -dir);
  e->pdf_back = vcm_pdf(s, sy, lambert_y, ny, nfy, -dir, light);
  e->cos_g = e->cos_s = fabs(dot(ngy, dir));
  e->sigma = 1.0f;
  return true;
}

/* The light vertex lv connected to the camera vertex (vcm_connect): T·f_c·G·f_l·Φ weighed against
 * every technique that makes the same path, times the thinning's stride and paths / Δλ. */
inline void vcm_connect_vertex(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                               const VcmVertex* cv, const VcmFactors* k, const __global KVcmLightVertex* lv,
                               int stride, float paths, __global float* out, float* rows) {
  float3 x = v->h.x, eye = -c->w.dir, y = load_float3(lv->position);
  float3 d = y - x;
  float dist2 = dot(d, d), dist = sqrt(dist2);
  float3 dir = d / dist;
  VcmEnd ec, el;
  Surface sy;
  if (!vcm_camera_end(s, v, cv, eye, dir, &ec) || !vcm_light_end(s, lv, dir, out + KASHA_BINS, &sy, &el)) return;
  bool medium_y = (lv->flags & KASHA_VCM_MEDIUM) != 0;
#if KASHA_MEDIA
  /* A collision leaves from the point itself; a surface off the side the connection leaves by. */
  bool medium_x = cv->medium >= 0;
  float3 off = medium_x ? (float3)(0.0f, 0.0f, 0.0f) : vcm_toward(cv->ng, dir);
  int start = medium_x ? c->w.medium : medium_after(s, v->h.tri, v->h.n, dir, c->w.medium);
  const __global float* tr;
  if (!segment_clear(s, x, off, medium_x ? 0.0f : v->h.eps, dir, dist, lv->eps / el.cos_g, start, &tr)) return;
  float tbar = vcm_unsampled(tr);
#else
  if (segment_occluded(s, x, vcm_toward(cv->ng, dir), v->h.eps, dir, dist, lv->eps / el.cos_g)) return;
  const float tbar = 1.0f;
#endif
  /* Merges at either end count where they are techniques: a light vertex's only with merges at
   * every vertex (else it lies behind the camera's merging vertex). */
  float vm_y = medium_y ? k->vm_volume : k->vm, vm_x = cv->medium >= 0 ? k->vm_volume : k->vm;
  bool merges_y = KASHA_VCM_MERGE_EVERY && (lv->flags & KASHA_VCM_MERGEABLE);
  float w_light = ec.pdf_out * el.cos_g / dist2 * (tbar * el.sigma) *
                  ((merges_y ? vm_y : 0.0f) + lv->dvcm + lv->dvc * el.pdf_back);
  float w_camera = el.pdf_out * ec.cos_g / dist2 * (tbar * ec.sigma) *
                   ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm_x : 0.0f) + c->dvcm + vcm_camera_dvc(c) * ec.pdf_back);
  float weight = 1.0f / (w_light + 1.0f + w_camera);
  if (!(weight > 0.0f)) return;
#if KASHA_SCATTERING
  if (medium_y)
    vcm_medium_light_apply(s, &s->media[lv->medium], load_float3(lv->position),
                           -load_float3(lv->arrival), -dir, vcm_vertex_power(lv), out);
  else
#endif
    vcm_light_apply(&sy, el.f, vcm_vertex_power(lv), out);
#if KASHA_MEDIA
  if (tr)
    for (int i = 0; i < KASHA_BINS; ++i) out[i] *= tr[i];
#endif
  float w = stride * weight * ec.cos_s * el.cos_s / dist2 * paths / s->bin_nm;
#if KASHA_SCATTERING
  if (cv->medium >= 0) {
    vcm_medium_camera_apply(&c->w.p, s, f, vcm_collision_medium(s, cv), eye, dir, out, w, rows);
    return;
  }
#endif
  vcm_camera_apply(&c->w.p, f, &v->surf, ec.f, out, w, rows);
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
                        const VcmVertex* cv, const VcmFactors* k, float paths, const __global float* store, int last,
                        uint u, __global float* out, float* rows) {
  if (last < 0) return;
  int n = vcm_vertex(store, last)->ordinal + 1;
  int stride = (n + KASHA_VCM_CONNECTIONS - 1) / KASHA_VCM_CONNECTIONS;
  int offset = (int)(u % (uint)stride);
  for (int slot = last; slot >= 0;) {
    const __global KVcmLightVertex* lv = vcm_vertex(store, slot);
    slot = lv->previous;
    if (lv->ordinal % stride != offset) continue;
    if (!VCM_LENGTH_COUNTS(c->w.depth + lv->depth + 3)) continue;
    vcm_connect_vertex(c, s, f, v, cv, k, lv, stride, paths, out, rows);
  }
}
