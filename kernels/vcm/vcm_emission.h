/* The light a camera path finds by hitting it: an emitter, or the infinite lights it leaves to. */

/* An emitting triangle the camera sees directly, its point drawn by light tracing too
 * (vcm_splat_light_point): the camera's weight, against the light subpaths' density of the point
 * by area (SmallVCM leaves this technique out; a lamp smaller than a pixel needs it). `dvcm`: the
 * camera side's dVCM on arrival, `paths` light subpaths over its camera paths. */
inline float vcm_seen_directly_weight(const SceneView* s, int emitter, float dvcm) {
  return 1.0f / (1.0f + s->emitter_area_pdf[emitter] * dvcm);
}

/* Emission hit by the camera path (SmallVCM's GetLightRadiance): seen directly, weighed against
 * light tracing's view of the light point; through delta bounces alone, whole; else weighed
 * against next-event estimation and light tracing. */
inline float vcm_emission_weight(const VcmCamera* c, const SceneView* s, const HitPoint* h) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + 1)) return 0.0f;
  /* ppm: no other technique reaches an emitter (merges are taken at the first vertex that
   * merges; this path went through delta or rough ones only). */
  if (KASHA_VCM_EMISSION_ONLY || !KASHA_VCM_CONNECT) return 1.0f;
  if (c->w.depth == 0) return vcm_seen_directly_weight(s, h->emitter, c->dvcm);
  float cos_light = dot(h->n, -c->w.dir);
  /* After a delta bounce next-event estimation could not have found it (dVCM 0). */
  float direct = c->dvcm > 0.0f ? vcm_direct_area(s, h->tri, c->w.prev_x, h->x, cos_light) : 0.0f;
  float w_camera =
      direct * c->dvcm + s->emitter_area_pdf[h->emitter] * cos_light * KASHA_INV_PI * vcm_camera_dvc(c);
  return 1.0f / (1.0f + w_camera);
}

#if KASHA_INFINITE_LIGHTS
/* A camera path that leaves the scene sees the infinite lights (SmallVCM's background in
 * GetLightRadiance): whole when seen directly, else each weighed against next-event estimation
 * of it (its direction's density, dVCM per solid angle: no hit turned it to area) and against
 * light subpaths leaving its disk. */
inline void vcm_escaped(const VcmCamera* c, const SceneView* s, const FilmView* f, float* rows) {
  if (!VCM_LENGTH_COUNTS(c->w.depth + 1)) return;
  for (int k = 0; k < s->light_sources; ++k) {
    const __global KLight* l = &s->lights[k];
    if (l->type != KASHA_LIGHT_INFINITE) continue;
    float weight = 1.0f;
    if (!KASHA_VCM_EMISSION_ONLY && KASHA_VCM_CONNECT && c->w.depth > 0) {
      float direct = infinite_light_pdf(s, l, c->w.dir);
      float emission = direct / (KASHA_PI * l->radius * l->radius);
      weight = 1.0f / (1.0f + direct * c->dvcm + emission * vcm_camera_dvc(c));
    }
    pw_add(&c->w.p, f, infinite_light_spectrum(s, l, c->w.dir), 0, weight, rows);
  }
}
#endif
