/* The light pass (SmallVCM's light subpath loop in RunIteration): a light subpath is a photon as
 * forward transport traces it (photon_transport.h), carrying 1/paths of the lights' power; at
 * each vertex with a non-delta part it is stored for connections and merges and, in the
 * connecting modes, splatted to the camera (light tracing), its partial MIS weights kept as
 * SmallVCM keeps them. */

/* A light vertex seen by the camera (light tracing, SmallVCM's ConnectToCamera): f Φ k / Δλ with
 * k = cos · importance (camera_connection), which is also the camera's density of the vertex per
 * area, weighed against every technique that samples it from the camera side — `spp` camera paths
 * a pixel against `paths` light subpaths. */
inline void vcm_splat(const SceneView* s, const FilmView* f, SplatTarget* t, const Surface* surf, float lambert,
                      bool merges, const HitPoint* h, float3 from, const Photon* p, float dvcm, float dvc,
                      const KVcmRadius* radius, float paths, int spp) {
  int pixel;
  float k;
  float3 to = camera_point(&s->camera, h->x) - h->x;
  /* The merge at this vertex, the camera path's first: its radius at the camera's distance. */
  float vm = vcm_merge_factor(vcm_eta_at(radius, vcm_radius_at(radius, length(to))));
  to = normalize(to);
  float3 nf = hit_front(h), ng = hit_ng(h);
  /* Off the geometric side the camera lies on, which the shading normal must agree with. */
  if (!hit_no_leak(h, to)) return;
  const __global float* tr;
  if (!camera_connection(s, h->x, vcm_toward(ng, to), h->eps, photon_medium_towards(s, p, h, to), &pixel, &k, &tr))
    return;
  VcmF fv = vcm_eval(s, surf, h->ns, nf, to, from, to, vcm_light_eta(surf));
  float nee = KASHA_VCM_DROP_DENSITY ? 0.0f : dvcm;
  float w_light = k * vcm_unsampled(tr) * spp / (KASHA_VCM_TRACING_SHARE * paths) *
                  ((merges ? vm : 0.0f) + nee + dvc * vcm_pdf(s, surf, lambert, h->ns, nf, to, from));
  k *= photon_arrival_correction(h, p->direction);
  float scale = k / (1.0f + w_light) / s->bin_nm;
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f)
    film_rows_conductor(f, p->power, tr, surf->eta_c, surf->k_c, surf->coat_c, fv.cos_m, scale * fv.conductor, rows);
#endif
  if (fv.lambert > 0.0f) {
#if KASHA_TRANSMISSION
    if (fv.through) film_rows(f, p->power, surf->tau, tr, scale * fv.lambert, rows);
    else
#endif
    if (surf->passive) film_rows(f, p->power, surf->rho, tr, scale * fv.lambert, rows);
#if KASHA_FLUORESCENCE
    if (surf->fluorescent)
      film_rows(f, 0, surf->ehat, tr, spectrum_dot(KASHA_BINS, p->power, surf->a, 0) * scale * fv.lambert, rows);
#endif
  }
  if (fv.white > 0.0f) film_rows(f, p->power, tr, 0, scale * fv.white, rows);
#if KASHA_DISPERSION
  if (fv.per_bin) {
    float pdf;
    for (int i = 0; i < KASHA_BINS; ++i) {
      if (p->power[i] == 0.0f) continue;
      float v = p->power[i] * (tr ? tr[i] : 1.0f) * scale * rough_dielectric_eval(fv.o, fv.i, surf->eta_bins[i], surf->alpha, true, &pdf);
#if KASHA_SPECTRAL_FILM
      rows[i] += v;
#else
      for (int r = 0; r < 3; ++r) rows[r] += f->cmf[r * KASHA_BINS + i] * v;
#endif
    }
  }
#endif
  if (film_rows_finite(rows)) splat_rows(t, pixel, rows);
}

/* The light point a subpath leaves from, seen by the camera (forward's view of a lamp): Le cos
 * importance / (p_A · paths), weighed against the camera's direct hit of it (vcm_emission_weight,
 * or vcm_seen_light's samples where the pixel's `seen` is set, which see through the media by
 * their transmittance, so no T̄ weighs them). SmallVCM leaves it out; a lamp smaller than a pixel
 * is found by this technique alone in practice. */
inline void vcm_splat_light_point(const SceneView* s, const FilmView* f, SplatTarget* t, const LightOrigin* o,
                                  const Photon* p, const KVcmIteration* it, const __global KVcmPixel* pixels) {
  int pixel;
  float k;
  const __global float* tr;
  if (!camera_connection(s, p->position, o->normal, o->eps, photon_medium(p), &pixel, &k, &tr)) return;
  bool seen = pixels[pixel].seen && it->seen_samples > 0;
  float samples = (float)it->spp * (seen ? it->seen_samples : 1);
  float w_camera = k * (seen ? 1.0f : vcm_unsampled(tr)) * samples /
                   (KASHA_VCM_TRACING_SHARE * (float)it->paths * o->area_pdf);
  float scale = k / ((1.0f + w_camera) * o->area_pdf * (float)it->paths);
#if KASHA_EMISSION_TEXTURES
  scale *= o->scale;
#endif
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  film_rows(f, 0, emitter_spectrum(s, o->emitter), tr, scale, rows);
  if (film_rows_finite(rows)) splat_rows(t, pixel, rows);
}

#if KASHA_SCATTERING
/* A light vertex at a collision in medium m seen by the camera (vcm_splat's, vcm_media.h): f Φ k
 * / Δλ with k the importance alone, weighed against the camera techniques by the camera's
 * pseudo-density of the collision, k T̄ σ̄. */
inline void vcm_splat_collision(const SceneView* s, const FilmView* f, SplatTarget* t, const __global KMedium* m,
                                bool merges, float3 x, const Photon* p, float dvcm, float dvc, const KVcmRadius* radius,
                                float paths, int spp) {
  int pixel;
  float k;
  const __global float* tr;
  if (!camera_connection_from_medium(s, x, p->medium, &pixel, &k, &tr)) return;
  float3 to = camera_point(&s->camera, x) - x, from = -p->direction;
  float vm = vcm_merge_factor(vcm_volume_eta(radius, vcm_radius_at(radius, length(to))));
  to = normalize(to);
  float nee = KASHA_VCM_DROP_DENSITY ? 0.0f : dvcm;
  float w_light = k * vcm_segment_mean(tr) * m->sigma_mean * spp / (KASHA_VCM_TRACING_SHARE * paths) *
                  ((merges ? vm : 0.0f) + nee + dvc * vcm_medium_pdf(m, to, from));
  float scale = k / (1.0f + w_light) / s->bin_nm;
  float rows[KASHA_FILM_ROWS];
  film_rows_clear(rows);
  collision_film_rows(s, f, m, p, to, tr, scale, rows);
  if (film_rows_finite(rows)) splat_rows(t, pixel, rows);
}

/* Stores the light vertex at the collision x in the photon's medium in record `slot`: no surface
 * (normals 0, triangle -1), its medium, KASHA_VCM_MEDIUM. */
inline void vcm_store_collision(__global float* store, int slot, float3 x, const Photon* p, int path, int depth,
                                float dvcm, float dvc, float dvm, int previous, int ordinal, bool merges) {
  __global KVcmLightVertex* v = (__global KVcmLightVertex*)(store + (long)slot * VCM_FLOATS);
  v->position[0] = x.x, v->position[1] = x.y, v->position[2] = x.z;
  v->normal[0] = v->normal[1] = v->normal[2] = 0.0f;
  v->shading[0] = v->shading[1] = v->shading[2] = 0.0f;
  v->path = path, v->depth = depth;
  __global float* power = (__global float*)(v + 1);
  for (int i = 0; i < KASHA_BINS; ++i) power[i] = p->power[i];
  v->arrival[0] = p->direction.x, v->arrival[1] = p->direction.y, v->arrival[2] = p->direction.z;
  v->dvcm = dvcm, v->dvc = dvc, v->dvm = dvm;
  v->triangle = -1, v->eps = 0.0f, v->previous = previous, v->ordinal = ordinal;
  v->barycentrics[0] = v->barycentrics[1] = 0.0f;
  v->flags = KASHA_VCM_MEDIUM | (merges ? KASHA_VCM_MERGEABLE : 0);
  v->instance = -1;
  v->medium = p->medium;
}
#endif

#if KASHA_SCATTERING
/* The light subpath's partial weights, as a collision's step takes them. */
typedef struct {
  float dvcm, dvc, dvm, dvc_merge;
} VcmPartial;

/* Light subpath `index`'s collision at x, its depth-th hit, in the photon's medium m (merging
 * there counts if it arrived from a delta bounce, `caustic`, or merges are not caustic ones):
 * stored after *last (the subpath's *ordinal-th), splatted to the camera, then scattered or
 * re-emitted (scatter_photon_in_medium) and the weights' step with the sphere's factors. False:
 * the path ends (the collision only absorbs, or the photon is absorbed). */
inline bool vcm_light_collision(const SceneView* s, const FilmView* f, const KVcmIteration* it, int index,
                                __global float* store, __global KVcmCounters* counters, SplatTarget* target,
                                Photon* p, Sampler* sampler, float3 x, int depth, bool caustic, int* last,
                                int* ordinal, VcmPartial* w) {
  const __global KMedium* m = &s->media[p->medium];
  if (!(m->events > 0.0f)) return false;
  const KVcmRadius* rad = &it->radius;
  bool merges = caustic || !KASHA_VCM_MERGE_CAUSTIC;
  float3 from = -p->direction;
  int slot = atomic_inc(&counters->stored);
  if (slot >= 0 && slot < it->capacity)
    vcm_store_collision(store, slot, x, p, index, depth, w->dvcm, w->dvc, w->dvm, *last, *ordinal, merges);
  *last = slot;
  ++*ordinal;
  if (KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY && VCM_LENGTH_COUNTS(depth + 2))
    vcm_splat_collision(s, f, target, m, merges, x, p, w->dvcm, w->dvc, rad, (float)it->paths, it->spp);
  if (scatter_photon_in_medium(p, s, x, sampler, depth) == BRANCH_ABSORBED) return false;
  float eta = vcm_volume_eta(rad, rad->radius), pdf = vcm_medium_pdf(m, from, p->direction);
  vcm_scattered_by(pdf, pdf, 1.0f, KASHA_VCM_MERGE_EVERY && merges, vcm_merge_factor(eta), vcm_connect_factor(eta),
                   &w->dvcm, &w->dvc, &w->dvm, &w->dvc_merge);
  return true;
}
#endif

/* A light subpath's partial MIS weights at its start (SmallVCM's GenerateLightSample): for a
 * light that is not a shape dVCM = direct / emission, dVC = 1 / (pick · emission), 0 for a delta
 * light (no camera path hits it); for an emitting triangle, emission by area and cosine,
 * p_e = p_A cos/π, against next-event estimation's pseudo-density p_A. *far_start: from a
 * distant or infinite light's disk (no t² at the first hit). */
inline void vcm_light_start(const SceneView* s, const LightOrigin* o, const Photon* p, float vc, float* dvcm,
                            float* dvc, float* dvm, bool* far_start) {
  *far_start = false;
  if (origin_in_medium(o)) {
    /* Inside an emitting medium (ppm alone, whose merges are unweighted): no other technique. */
    *dvcm = *dvc = *dvm = 0.0f;
    return;
  }
#if KASHA_LIGHT_SOURCES
  if (o->source) {
    const __global KLight* l = o->source;
    float direct, emission = vcm_source_emission(s, l, p->direction, &direct);
    bool delta = l->type != KASHA_LIGHT_INFINITE;
    *dvcm = direct / emission;
    *dvc = delta ? 0.0f : 1.0f / (l->pick * emission);
    *dvm = *dvc * vc;
    *far_start = !vcm_source_finite(l);
    return;
  }
#endif
  float cos_light = dot(o->normal, p->direction);
  *dvcm = KASHA_PI / cos_light, *dvc = KASHA_PI / o->area_pdf, *dvm = *dvc * vc;
}

/* Stores the light vertex at hit h in record `slot` (vcm_records.h): where it is, how the light
 * arrived, the subpath's weights there and its previous stored vertex. */
inline void vcm_store_vertex(__global float* store, int slot, const HitPoint* h, const Photon* p, int path, int depth,
                             float dvcm, float dvc, float dvm, int previous, int ordinal, bool merges) {
  __global KVcmLightVertex* v = (__global KVcmLightVertex*)(store + (long)slot * VCM_FLOATS);
  float3 ng = hit_ng(h);
  v->position[0] = h->x.x, v->position[1] = h->x.y, v->position[2] = h->x.z;
  v->normal[0] = ng.x, v->normal[1] = ng.y, v->normal[2] = ng.z;
  v->path = path, v->depth = depth;
  float arrival = photon_arrival_correction(h, p->direction);
  __global float* power = (__global float*)(v + 1);
  for (int i = 0; i < KASHA_BINS; ++i) power[i] = p->power[i] * arrival;
  v->arrival[0] = p->direction.x, v->arrival[1] = p->direction.y, v->arrival[2] = p->direction.z;
  v->dvcm = dvcm, v->dvc = dvc, v->dvm = dvm;
  v->triangle = h->tri, v->eps = h->eps, v->previous = previous, v->ordinal = ordinal;
#if KASHA_TEXTURES
  v->barycentrics[0] = h->b.x, v->barycentrics[1] = h->b.y;
#else
  v->barycentrics[0] = v->barycentrics[1] = 0.0f;
#endif
  v->flags = (merges ? KASHA_VCM_MERGEABLE : 0) | (h->front ? KASHA_VCM_FRONT : 0);
  v->shading[0] = h->ns.x, v->shading[1] = h->ns.y, v->shading[2] = h->ns.z;
#if KASHA_INSTANCES
  v->instance = h->instance;
#else
  v->instance = -1;
#endif
  v->medium = -1;
}

/* Light subpath `index` of the iteration, from the stream of its index: its vertices stored (past
 * the store's capacity they are counted but not written: the host grows the store and runs the
 * chunk again), *last its last stored one's record. Returns the power the depth guard cut, per
 * its start. */
inline float vcm_light_path(const SceneView* s, const FilmView* f, const KVcmIteration* it, int index,
                            __global float* store, __global KVcmCounters* counters, SplatTarget* target,
                            const __global KVcmPixel* pixels, __global int* last_stored) {
  /* The global radius's factors (per_unit > 0: dVM is not read, and merges count only where
   * light tracing splats). */
  const KVcmRadius* rad = &it->radius;
  const float vm = vcm_merge_factor(vcm_eta_at(rad, rad->radius)), vc = vcm_connect_factor(vcm_eta_at(rad, rad->radius));
  const float paths = (float)it->paths;
  Sampler sampler = photon_sampler(it->seed, it->pass, it->paths, index);
  LightOrigin o;
  /* ppm's light subpaths also start in emitting media (vcm's and bpt's camera paths take that
   * light whole, so their light subpaths must not). */
  Photon p = emit_photon(s, paths, !KASHA_VCM_CONNECT, &sampler, &o);
  *last_stored = -1;
  if (origin_in_medium(&o) && !(p.start > 0.0f)) return 0.0f; /* drawn where the medium emits nothing */
  const float3 start = p.position;
  p.position += o.normal * o.eps;
  float dvcm, dvc, dvm;
  bool far_start;
  vcm_light_start(s, &o, &p, vc, &dvcm, &dvc, &dvm, &far_start);
  if (KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY && VCM_LENGTH_COUNTS(1) && o.tri >= 0)
    vcm_splat_light_point(s, f, target, &o, &p, it, pixels);
  int last = -1, ordinal = 0;
  float guard = 0.0f, dvc_merge = 0.0f; /* the light side leaves its own merges out */
  bool caustic = false;                  /* it arrives from a delta bounce */
#if KASHA_SCATTERING
  float sigma_prev = 1.0f; /* σ̄ where the segment now flown started (vcm_media.h) */
#endif
  for (int depth = origin_depth(&o);; ++depth) {
    if (depth == KASHA_MAX_PATH_DEPTH) {
      guard = photon_total(&p) / p.start;
      break;
    }
#ifdef KASHA_DEPTH_CAP
    /* A vertex at hit k makes paths of at least k + 1 scattering vertices. */
    if (depth >= KASHA_DEPTH_CAP) break;
#endif
    HitPoint h;
#if KASHA_SCATTERING
    float tbar;
    int reached = photon_flight(&p, s, &sampler, depth, &h, &tbar);
    if (reached == KASHA_FLIGHT_ESCAPED) break;
    const bool collided = reached == KASHA_FLIGHT_SCATTERED;
#else
    if (!photon_intersect(s, &p, &h)) break;
    const bool collided = false;
#endif
    vcm_arrived(far_start && depth == 0 ? 1.0f : h.t, collided ? 1.0f : fabs(dot(h.n, p.direction)), &dvcm, &dvc,
                &dvm, &dvc_merge);
    /* dVCM's next-event density (SmallVCM's directPdfA, by area above) as it truly is from here. */
    if (depth == 0 && o.tri >= 0)
      dvcm *= vcm_direct_area(s, o.tri, h.x, start, dot(o.normal, p.direction)) / o.area_pdf;
#if KASHA_SCATTERING
    const __global KMedium* m = collided ? &s->media[p.medium] : 0;
    vcm_through(tbar, sigma_prev, collided ? m->sigma_mean : 1.0f, &dvcm, &dvc, &dvm,
                &dvc_merge);
    sigma_prev = collided ? m->sigma_mean : 1.0f;
    if (collided) {
      VcmPartial w = {dvcm, dvc, dvm, dvc_merge};
      if (!vcm_light_collision(s, f, it, index, store, counters, target, &p, &sampler, h.x, depth, caustic, &last,
                               &ordinal, &w))
        break;
      dvcm = w.dvcm, dvc = w.dvc, dvm = w.dvm, dvc_merge = w.dvc_merge;
      caustic = false;
      continue;
    }
#endif
#if KASHA_SHADING_NORMALS
    /* From below the shading normal's hemisphere: the surface does not scatter it (hit_seen). */
    if (!hit_seen(&h, p.direction)) break;
#endif
    Surface surf;
    load_surface_at(s, &h, &surf);
    float lambert = vcm_lambert_mean(&surf);
    /* A merge here is a technique (caustic merges: only from a delta bounce). */
    bool merges = vcm_mergeable(&surf) && (caustic || !KASHA_VCM_MERGE_CAUSTIC);
    float3 from = -p.direction, nf = hit_front(&h), ng = hit_ng(&h);
    if (vcm_connectible(&surf)) {
      int slot = atomic_inc(&counters->stored);
      if (slot >= 0 && slot < it->capacity)
        vcm_store_vertex(store, slot, &h, &p, index, depth, dvcm, dvc, dvm, last, ordinal, merges);
      last = slot;
      ++ordinal;
      if (KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY && VCM_LENGTH_COUNTS(depth + 2))
        vcm_splat(s, f, target, &surf, lambert, merges, &h, from, &p, dvcm, dvc, rad, paths, it->spp);
    }
    int branch = scatter_photon(&p, &surf, s, &h, &sampler, depth);
    if (branch == BRANCH_ABSORBED) break;
    bool delta = (branch == BRANCH_SPECULAR && !surface_rough(&surf)) || (branch == BRANCH_GLOSS && surf.mirror);
    caustic = delta;
    if (!vcm_scattered(s, &surf, lambert, h.ns, nf, ng, from, p.direction, delta, KASHA_VCM_MERGE_EVERY && merges,
                       vm, vc, &dvcm, &dvc, &dvm, &dvc_merge))
      break;
  }
  *last_stored = last;
  return guard;
}
