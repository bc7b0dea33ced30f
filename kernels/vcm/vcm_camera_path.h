/* A camera path of the camera pass (SmallVCM's camera subpath loop in RunIteration): from the
 * camera, at each vertex the emission it hits, then at a vertex with a non-delta part its
 * techniques — next-event estimation, connections to its light subpath and merges with the stored
 * light vertices — each MIS-weighted, then the bounce, its partial weights kept as SmallVCM keeps
 * them. */

/* What the camera vertex's techniques share (VcmVertex). Merging here: a vertex whose material
 * merges and (--merges first) no vertex before it that is not delta, *met (ppm merges once, at
 * the first that merges). */
inline VcmVertex vcm_camera_vertex(const CameraVertex* v, bool* met) {
  VcmVertex cv;
  cv.ns = v->h.ns;
  cv.nf = hit_front(&v->h);
  cv.ng = hit_ng(&v->h);
  cv.lambert = vcm_lambert_mean(&v->surf);
  if (KASHA_VCM_MERGE_EVERY || !KASHA_VCM_CONNECT)
    cv.merges = vcm_mergeable(&v->surf);
  else
    cv.merges = vcm_mergeable(&v->surf) && !*met;
  *met = *met || vcm_connectible(&v->surf);
  cv.eta = 1.0f;
  cv.medium = -1;
  cv.sparse = 1.0f;
  return cv;
}

/* The techniques at a camera vertex with a non-delta part, its merging radius r_merge and
 * factors k (a collision's: the sphere's, vcm_media.h). In vcm and bpt: next-event estimation
 * and connections where the light subpath is the chunk's, merges (vcm) with every chunk. In ppm
 * the first vertex that merges merges all of it, unless a mirror lobe chosen by its probability
 * carries the path on: false then, the path ends. */
inline bool vcm_camera_techniques(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                  const VcmVertex* cv, const VcmCameraInputs* in, float r_merge, const VcmFactors* k,
                                  float* rows) {
  const KVcmIteration* it = in->it;
  float scale = KASHA_INV_PI / (r_merge * r_merge * s->bin_nm), vm = k->vm, vc = k->vc;
#if KASHA_SCATTERING
  const __global KMedium* m = vcm_collision_medium(s, cv);
  if (m) scale *= 0.75f / r_merge, vm = k->vm_volume, vc = k->vc_volume; /* the sphere's volume */
#endif
  if (KASHA_VCM_CONNECT) {
    if (in->own) {
      if (VCM_LENGTH_COUNTS(c->w.depth + 2)) {
#if KASHA_SCATTERING
        if (m) vcm_next_event_collision(c, s, f, v, cv, m, vm, rows);
        else
#endif
          vcm_next_event(c, s, f, v, cv, vm, rows);
      }
      uint seed = hash_combine(it->seed ^ 0x2545f491u, it->pass);
      vcm_connect(c, s, f, v, cv, k, (float)it->paths, in->store, in->light_paths[in->partner - it->chunk_first].last,
                  hash_combine(hash_combine(seed, (uint)in->partner), (uint)c->w.depth), in->out, rows);
    }
#if KASHA_VCM_MERGE
    if (cv->merges) vcm_merge(c, s, f, v, cv, vc, r_merge, scale, in->store, in->grid, it->inv_cell, it->mask, rows);
#endif
    return true;
  }
#if KASHA_SCATTERING
  if (m) {
    vcm_merge(c, s, f, v, cv, vc, r_merge, scale, in->store, in->grid, it->inv_cell, it->mask, rows);
    return false;
  }
#endif
  float p_mirror = v->surf.mirror && !surface_specular(&v->surf) ? v->probs.x : 0.0f;
  if (cv->merges && !(v->u_choice.x < p_mirror)) {
    vcm_merge(c, s, f, v, cv, vc, r_merge, scale / (1.0f - p_mirror), in->store, in->grid, it->inv_cell, it->mask,
              rows);
    return false;
  }
  return true;
}

/* The bounce at a vertex with a non-delta part, by the branch its probabilities choose (a rough
 * interface: its direction from the visible normals, walk_rough_scatter). False: the path ends. */
inline bool vcm_camera_bounce(VcmCamera* c, const SceneView* s, const FilmView* f, CameraVertex* v, float eta,
                              Sampler* sampler) {
#if KASHA_ROUGH
  if (surface_rough(&v->surf)) return walk_rough_scatter(&c->w, v, eta);
#endif
  float3 probs = v->probs;
  float choice = v->u_choice.x;
  if (choice < probs.x) return walk_gloss(&c->w, s, v, sampler);
  if (choice < probs.x + probs.y || probs.z <= 0.0f) {
    passive_bounce(&c->w, v, probs.y);
    return true;
  }
#if KASHA_FLUORESCENCE
  lambert_bounce(&c->w, v, probs.z);
  pw_scatter_fluorescent(&c->w.p, f, v->surf.ehat, v->surf.a, lambert_weight(&c->w, v) / probs.z);
#if KASHA_DISPERSION
  c->w.bin = -1; /* re-emission spreads the path over the excitation spectrum again */
#endif
#endif
  return true;
}

/* The camera path's flight to its next vertex: KASHA_FLIGHT_SURFACE (h the hit), _SCATTERED (a
 * collision at h->x in the walk's medium, vcm_media.h) or _ESCAPED, the partial weights turned to
 * the vertex (to the direction's measure on escaping); -1: the path carries nothing on. */
inline int vcm_camera_next(VcmCamera* c, const SceneView* s, const FilmView* f, Sampler* sampler, HitPoint* h) {
#if KASHA_SCATTERING
  float tbar;
  sampler_at(sampler, 1 + c->w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX + 4);
  int reached = flight(&c->w.p, s, f, c->w.org, c->w.dir, &c->w.medium, sample_2d(sampler), h, &tbar);
  if (!(tbar > 0.0f)) return -1;
  bool collided = reached == KASHA_FLIGHT_SCATTERED;
  float sigma = collided ? s->media[c->w.medium].sigma_mean : 1.0f;
#else
  int reached = walk_intersect(&c->w, s, h) ? KASHA_FLIGHT_SURFACE : KASHA_FLIGHT_ESCAPED;
  const bool collided = false;
#endif
  if (reached != KASHA_FLIGHT_ESCAPED) {
    vcm_arrived(h->t, collided ? 1.0f : fabs(dot(h->n, c->w.dir)), &c->dvcm, &c->dvc, &c->dvm, &c->dvc_merge);
    /* The orthographic camera's density is per area from the start (camera_pixel_solid_angle). */
    if (c->w.depth == 0 && s->camera.type == KASHA_CAMERA_ORTHOGRAPHIC) c->dvcm /= h->t * h->t;
  }
#if KASHA_SCATTERING
  vcm_through(tbar, c->sigma_prev, sigma, &c->dvcm, &c->dvc, &c->dvm, &c->dvc_merge);
  c->sigma_prev = sigma;
#endif
  return reached;
}

#if KASHA_SCATTERING
/* A camera path's collision in its medium (vcm_media.h): its samples and branches, its techniques
 * with the sphere's factors (the radius, and *k, the merging vertex's where the radius is the
 * path's), then the bounce (walk_medium_scatter) and the weights' step. False: the path ends. */
inline bool vcm_camera_collision(VcmCamera* c, const SceneView* s, const FilmView* f, Sampler* sampler,
                                 CameraVertex* v, const VcmCameraInputs* in, float travelled, bool* met,
                                 float* r_merge, VcmFactors* k, float* rows) {
  const __global KMedium* m = &s->media[c->w.medium];
  float probs[1 + KASHA_MEDIUM_FLUOROPHORES];
  v->in_medium = true;
#if KASHA_MEDIUM_EMISSION
  /* The medium's emission at the collision counts whole: vcm's and bpt's light subpaths never
   * start in a medium, and ppm's, which do, make paths through a merge here (another vertex).
   * Once per camera path (`own`: the path is replayed for each chunk of light subpaths), and, as
   * pbrt-v4's volpath, only below the --max-depth cap (the collision would be one vertex more). */
  bool emits = in->own && VCM_LENGTH_COUNTS(c->w.depth + 1);
#ifdef KASHA_DEPTH_CAP
  emits = emits && c->w.depth < KASHA_DEPTH_CAP;
#endif
  if (emits) medium_emission_add(&c->w.p, s, f, c->w.medium, v->h.x, rows);
#endif
  if (!walk_medium_samples(&c->w, sampler, v) || !medium_branches(&c->w, s, f, m, probs)) return false;
  VcmVertex cv;
  cv.ns = cv.nf = cv.ng = (float3)(0.0f, 0.0f, 0.0f);
  cv.lambert = 0.0f;
  cv.eta = 1.0f;
  cv.medium = c->w.medium;
  cv.sparse = medium_inverse_density(s, c->w.medium, v->h.x);
  cv.merges = KASHA_VCM_MERGE_EVERY || !KASHA_VCM_CONNECT || !*met;
  *met = true;
  const KVcmRadius* radius = &in->it->radius;
  if (cv.merges && radius->per_unit > 0.0f) {
    *r_merge = vcm_radius_at(radius, travelled);
    *k = vcm_factors(radius, *r_merge);
  }
  if (!KASHA_VCM_EMISSION_ONLY && !vcm_camera_techniques(c, s, f, v, &cv, in, *r_merge, k, rows)) return false;
  float3 eye = -c->w.dir;
  if (!walk_medium_scatter(&c->w, s, f, v, m, probs)) return false;
  vcm_camera_decide(c, false);
  float pdf = vcm_medium_pdf(m, eye, c->w.dir);
  vcm_scattered_by(pdf, pdf, 1.0f, cv.merges, k->vm_volume, k->vc_volume, &c->dvcm, &c->dvc, &c->dvm,
                   &c->dvc_merge);
  return true;
}
#endif

/* One camera path of the iteration, one of the `spp` the pixel has, with its light subpath
 * in->partner (VcmCameraInputs). Returns what it still carried (relative to its start) if the
 * depth guard cut it. */
inline float vcm_camera_path(const SceneView* s, const FilmView* f, int pixel, Sampler* sampler,
                             const VcmCameraInputs* in, float* rows) {
  const KVcmRadius* radius = &in->it->radius;
  const bool own = in->own, seen_apart = in->seen_apart;
  /* The factors of the global radius; where the radius is the path's, of its merging vertex's. */
  float r_merge = radius->radius;
  VcmFactors k = vcm_factors(radius, r_merge);
  float travelled = 0.0f;
  VcmCamera c;
  float3 o, dir = camera_ray(&s->camera, pixel, sampler, &o);
  walk_start(&c.w, s, f, o, dir);
  vcm_camera_start(s, dir, (float)in->it->paths, in->it->spp, &c);
  CameraVertex v;
  bool met = false;       /* a vertex that is not delta is behind */
  bool delta_only = true; /* every bounce so far was delta (vcm_seen_light's paths) */
  while (c.w.depth < KASHA_MAX_PATH_DEPTH) {
    HitPoint* h = &v.h;
    int reached = vcm_camera_next(&c, s, f, sampler, h);
    if (reached == KASHA_FLIGHT_ESCAPED) {
#if KASHA_INFINITE_LIGHTS
      if (own && !(seen_apart && delta_only)) vcm_escaped(&c, s, f, rows);
#endif
      return 0.0f;
    }
    if (reached < 0) return 0.0f;
    travelled += h->t;
#if KASHA_SCATTERING
    if (reached == KASHA_FLIGHT_SCATTERED) {
      if (!vcm_camera_collision(&c, s, f, sampler, &v, in, travelled, &met, &r_merge, &k, rows)) return 0.0f;
      delta_only = false;
      continue;
    }
    v.in_medium = false;
#endif
    if (own && h->emitter >= 0 && h->front && !(seen_apart && delta_only)) {
      float weight = vcm_emission_weight(&c, s, h);
#if KASHA_EMISSION_TEXTURES
      weight *= emission_factor(s, h->tri, h->b.x, h->b.y);
#endif
      pw_add(&c.w.p, f, emitter_spectrum(s, h->emitter), 0, weight, rows);
    }
#ifdef KASHA_DEPTH_CAP
    /* Every technique from here on makes a path of more scattering vertices than the cap. */
    if (c.w.depth >= KASHA_DEPTH_CAP) return 0.0f;
#endif
#if KASHA_SHADING_NORMALS
    /* Seen from below the shading normal's hemisphere, the surface scatters nothing (hit_seen). */
    if (!hit_seen(h, c.w.dir)) return 0.0f;
#endif
    load_surface_at(s, h, &v.surf);
    v.probs = surface_specular(&v.surf) ? (float3)(1.0f, 0.0f, 0.0f) : branch_probabilities(&c.w.p, f, &v.surf);
    if (v.probs.x + v.probs.y + v.probs.z <= 0.0f) return 0.0f;
    sampler_at(sampler, 1 + c.w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
    v.u_choice = sample_2d(sampler);
    v.u_light = sample_2d(sampler);
    v.u_dir = sample_2d(sampler);
    float3 eye = -c.w.dir;
    VcmVertex cv = vcm_camera_vertex(&v, &met);
    if (cv.merges && radius->per_unit > 0.0f) {
      r_merge = vcm_radius_at(radius, travelled);
      k = vcm_factors(radius, r_merge);
    }
    bool rough = surface_rough(&v.surf);
#if KASHA_ROUGH && KASHA_DIELECTRIC
    /* A rough dielectric's index, a dispersive one's at the path's bin (chosen here on the
     * vertex's fourth sample pair if the path has none, as walk_rough does). */
    if (rough && v.surf.kind == KASHA_KIND_DIELECTRIC) {
      cv.eta = walk_eta(&c.w, f, &v.surf, sample_2d(sampler).x);
      if (cv.eta < 0.0f) return 0.0f;
    }
#endif
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf) && !rough) {
      if (!walk_specular(&c.w, f, &v)) return 0.0f;
      vcm_camera_decide(&c, true);
      vcm_scattered(s, &v.surf, 0.0f, h->ns, cv.nf, cv.ng, eye, c.w.dir, true, false, k.vm, k.vc, &c.dvcm, &c.dvc,
                    &c.dvm, &c.dvc_merge);
      if (!walk_on(&c.w, s, f, &v)) return 0.0f;
      continue;
    }
#endif
    if (vcm_connectible(&v.surf) && !KASHA_VCM_EMISSION_ONLY &&
        !vcm_camera_techniques(&c, s, f, &v, &cv, in, r_merge, &k, rows))
      return 0.0f;
    if (!vcm_camera_bounce(&c, s, f, &v, cv.eta, sampler)) return 0.0f;
    vcm_camera_decide(&c, c.w.specular);
    if (!vcm_scattered(s, &v.surf, cv.lambert, h->ns, cv.nf, cv.ng, eye, c.w.dir, c.w.specular, cv.merges, k.vm,
                       k.vc, &c.dvcm, &c.dvc, &c.dvm, &c.dvc_merge))
      return 0.0f;
    delta_only = delta_only && c.w.specular;
    if (!walk_on(&c.w, s, f, &v)) return 0.0f;
  }
  return walk_cut(&c.w, f);
}
