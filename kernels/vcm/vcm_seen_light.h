/* dVCM of the walk's direct view of h along d: a camera path's start (vcm_camera_start) for the
 * pixel's spp · seen samples, arrived at h. The walk attenuates by the media's transmittance in
 * place of sampling a free flight, so no T̄ divides it (vcm_media.h). */
inline float vcm_seen_dvcm(const SceneView* s, const KVcmIteration* it, int seen, float3 d, const HitPoint* h) {
  VcmCamera c;
  vcm_camera_start(s, d, (float)it->paths, it->spp * seen, &c);
  vcm_arrived(h->t, fabs(dot(h->n, d)), &c.dvcm, &c.dvc, &c.dvm, &c.dvc_merge);
  if (s->camera.type == KASHA_CAMERA_ORTHOGRAPHIC) c.dvcm /= h->t * h->t;
  return c.dvcm;
}

/* Light the camera sees directly or through delta bounces alone — a lamp, the sky, their images
 * in glass, a mirror or a smooth coat — on a walk of its own that takes only delta bounces. No
 * other technique reaches such a path (next-event estimation, connections and merges need a
 * bounce that is not delta; dVCM and dVC are 0 along it), so its MIS weight is 1 and a pixel may
 * take it from more samples than it has full camera paths: a lamp's edges and its highlight on a
 * coat converge with a pixel's samples, and these cost a ray or two, a full camera path tens. At
 * a surface that also scatters otherwise (a coat, a gloss lobe over a Lambert part) the walk
 * takes the delta lobe always, weighed by its albedo, where the full path picks it with a
 * probability: the same expectation, without the full path's rare bright picks. Bounces and
 * roulette otherwise as vcm_camera_path's. The one technique beside it: light tracing's view of a
 * lamp seen directly (vcm_splat_light_point), weighed against this walk's `seen` samples a camera
 * path. */
inline float vcm_seen_light(const SceneView* s, const FilmView* f, const KVcmIteration* it, int seen, int pixel,
                            Sampler* sampler, float* rows) {
  CameraWalk w;
  float3 o, d = camera_ray(&s->camera, pixel, sampler, &o);
  walk_start(&w, s, f, o, d);
  CameraVertex v;
  while (w.depth < KASHA_MAX_PATH_DEPTH) {
    HitPoint* h = &v.h;
    if (!walk_intersect(&w, s, h)) {
#if KASHA_INFINITE_LIGHTS
      if (VCM_LENGTH_COUNTS(w.depth + 1)) walk_escaped(&w, s, f, rows); /* whole: w.specular */
#endif
      return 0.0f;
    }
    if (h->emitter >= 0 && h->front && VCM_LENGTH_COUNTS(w.depth + 1)) {
      float weight = 1.0f;
      if (w.depth == 0 && KASHA_VCM_CONNECT && !KASHA_VCM_EMISSION_ONLY)
        weight = vcm_seen_directly_weight(s, h->emitter, vcm_seen_dvcm(s, it, seen, d, h));
#if KASHA_EMISSION_TEXTURES
      weight *= emission_factor(s, h->tri, h->b.x, h->b.y);
#endif
      pw_add(&w.p, f, emitter_spectrum(s, h->emitter), 0, weight, rows);
    }
#if KASHA_SHADING_NORMALS
    if (!hit_seen(h, w.dir)) return 0.0f;
#endif
    load_surface_at(s, h, &v.surf);
    if (surface_rough(&v.surf)) return 0.0f;
    sampler_at(sampler, 1 + w.depth * KASHA_CAMERA_PAIRS_PER_VERTEX);
    v.u_choice = sample_2d(sampler);
    v.u_light = sample_2d(sampler);
    v.u_dir = sample_2d(sampler);
#if KASHA_DIELECTRIC || KASHA_CONDUCTOR
    if (surface_specular(&v.surf)) {
      if (!walk_specular(&w, f, &v)) return 0.0f;
    } else
#endif
    {
      if (!(v.surf.g > 0.0f && v.surf.mirror)) return 0.0f;
      w.dir = reflect_dir(w.dir, h->ns);
      pw_scatter_diagonal(&w.p, 0, v.surf.g);
    }
    if (!walk_on(&w, s, f, &v)) return 0.0f;
  }
  return walk_cut(&w, f);
}
