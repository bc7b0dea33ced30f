#if KASHA_MEDIA
/* The light le as it arrives over a connection of transmittance tr (segment_clear's, in the
 * scratch; null: 1): tr∘le, in the scratch. */
inline const __global float* vcm_through_light(const SceneView* s, const __global float* tr,
                                               const __global float* le) {
  if (!tr) return le;
  __global float* out = s->scratch + KASHA_SCRATCH_MEDIA;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] *= le[i];
  return out;
}
#endif

/* Next-event estimation's light point lp, at dist along wi and drawn with density pdf_light: its
 * density as next-event estimation samples it (*direct, SmallVCM's directPdfW) and the emission
 * technique's (*emission), and the weight against it of the camera path sampling wi with the
 * pseudo-density pdf_dir (its reach included). A point or spot light: cos_l is 1, its direct
 * density per solid angle d² (its 1/d² is in the contribution), and a delta light is found by
 * nothing else; a lamp: the density it was drawn with, as the weights at the lamp's hits. */
inline float vcm_light_point_weight(const SceneView* s, const LightPoint* lp, float3 wi, float dist, float cos_l,
                                    float pdf_light, float pdf_dir, float* direct, float* emission) {
#if KASHA_LIGHT_SOURCES
  if (lp->source) {
    const __global KLight* l = lp->source;
    *emission = vcm_source_emission(s, l, -wi, direct);
    if (vcm_source_finite(l)) *direct *= dist * dist;
    return lp->delta ? 0.0f : pdf_dir / (l->pick * *direct);
  }
#endif
  *direct = pdf_light, *emission = s->emitter_area_pdf[lp->emitter] * cos_l * KASHA_INV_PI;
  return pdf_dir / *direct;
}

/* Next-event estimation at a camera vertex (SmallVCM's DirectIllumination): one light point as
 * next_event.h samples it, weighed against the camera path hitting it and against every
 * technique that reaches it from the light's side. A rough dielectric takes light from either
 * side. */
inline void vcm_next_event(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                           const VcmVertex* cv, float vm, float* rows) {
  if (s->light_count == 0) return;
  const Surface* surf = &v->surf;
  float3 x = v->h.x, ns = cv->ns, eye = -c->w.dir;
  float pdf_light;
  LightPoint lp = sample_light_from(s, x, v->u_light, &pdf_light);
  if (!(pdf_light > 0.0f)) return;
  float3 to = lp.position - x;
  float dist = length(to);
  if (!(dist > v->h.eps + lp.eps)) return;
  float3 wi = to / dist;
  float cos_x = fabs(dot(ns, wi)), cos_g = fabs(dot(cv->ng, wi)), cos_l = -dot(lp.normal, wi);
  if (cos_x <= 0.0f || cos_l <= 0.0f || !hit_no_leak(&v->h, wi)) return;
  VcmF fv = vcm_eval(s, surf, ns, cv->nf, eye, wi, wi, cv->eta);
  if (!vcm_f_nonzero(&fv)) return;
  const __global float* le = light_point_spectrum(s, &lp);
#if KASHA_MEDIA
  /* The light through the media on the way; T̄ of the segment for the weights (vcm_media.h). */
  const __global float* tr;
  if (!segment_clear(s, x, vcm_toward(cv->ng, wi), v->h.eps, wi, dist, lp.eps / cos_l,
                     medium_after(s, v->h.tri, v->h.n, wi, c->w.medium), &tr))
    return;
  float tbar = vcm_unsampled(tr);
  le = vcm_through_light(s, tr, le);
#else
  if (segment_occluded(s, x, vcm_toward(cv->ng, wi), v->h.eps, wi, dist, lp.eps / cos_l)) return;
  const float tbar = 1.0f;
#endif
  float direct, emission;
  float w_light = vcm_light_point_weight(s, &lp, wi, dist, cos_l, pdf_light,
                                         vcm_pdf(s, surf, cv->lambert, ns, cv->nf, eye, wi) * tbar, &direct, &emission);
  /* The light part is the light point: with caustic merges no merge here or behind makes it. */
  float w_camera = emission * cos_g * tbar / (direct * cos_l) *
                   ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm : 0.0f) + c->dvcm +
                    vcm_camera_dvc(c) * vcm_pdf(s, surf, cv->lambert, ns, cv->nf, wi, eye));
  float weight = 1.0f / (w_light + 1.0f + w_camera);
  float scale = cos_x / pdf_light * weight;
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  scale *= lp.scale;
#endif
  vcm_camera_apply(&c->w.p, f, surf, fv, le, scale, rows);
}

#if KASHA_SCATTERING
/* Next-event estimation at a camera path's collision in m (vcm_media.h): one light point, its
 * light sent on by σs and the phase function and by each dye, weighed as at a surface with the
 * collision's densities — the phase mix by solid angle, T̄ σ̄ to reach it, no cosine. */
inline void vcm_next_event_collision(const VcmCamera* c, const SceneView* s, const FilmView* f, const CameraVertex* v,
                                     const VcmVertex* cv, const __global KMedium* m, float vm, float* rows) {
  if (s->light_count == 0) return;
  float3 x = v->h.x, eye = -c->w.dir, wi;
  float pdf_light, dist, cos_l;
  LightPoint lp;
  if (!collision_light_point(s, x, v->u_light, &lp, &pdf_light, &wi, &dist, &cos_l)) return;
  const __global float* tr;
  if (!segment_clear(s, x, (float3)(0.0f, 0.0f, 0.0f), 0.0f, wi, dist, lp.eps / cos_l, c->w.medium, &tr)) return;
  float tbar = vcm_segment_mean(tr), pdf = vcm_medium_pdf(m, eye, wi);
  const __global float* le = vcm_through_light(s, tr, light_point_spectrum(s, &lp));
  float direct, emission;
  float w_light = vcm_light_point_weight(s, &lp, wi, dist, cos_l, pdf_light, pdf * tbar, &direct, &emission);
  float w_camera = emission * tbar * m->sigma_mean / (direct * cos_l) *
                   ((cv->merges && !KASHA_VCM_MERGE_CAUSTIC ? vm : 0.0f) + c->dvcm + vcm_camera_dvc(c) * pdf);
  float scale = 1.0f / (pdf_light * (w_light + 1.0f + w_camera));
#if KASHA_LIGHT_SOURCES || KASHA_EMISSION_TEXTURES
  scale *= lp.scale;
#endif
  vcm_medium_camera_apply(&c->w.p, s, f, m, eye, wi, le, scale, rows);
}
#endif
