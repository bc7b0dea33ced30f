/* f at a vertex (SmallVCM's BSDF Evaluate), split by how each part colours, and its product with
 * a light subpath's spectrum or a camera path's colour. */

/* f(wo, wi) of a vertex's non-delta parts for radiance going from wi to wo (both away from the
 * surface; ns on the side it was met from, nf the front), split by how each part colours: the
 * Lambert parts' factor (1/π, times a coat's t t / η² with `other` the direction it was not met
 * from), a white part (tabulated or coat lobe, rough dielectric) and a rough conductor's f before
 * its F(λ) at cos_m. */
typedef struct {
  float lambert, white, conductor, cos_m;
#if KASHA_TRANSMISSION
  bool through; /* the Lambert part between opposite sides: τ in place of ρ (surface.h) */
#endif
#if KASHA_DISPERSION
  bool per_bin; /* a rough dispersive dielectric met by a spectrum: f bin by bin at o, i */
  float3 o, i;
#endif
} VcmF;

inline bool vcm_f_nonzero(const VcmF* fv) {
#if KASHA_DISPERSION
  if (fv->per_bin) return true;
#endif
  return fv->lambert > 0.0f || fv->white > 0.0f || fv->conductor > 0.0f;
}

/* eta: a rough dielectric's index for this path (a dispersive one's at the path's bin), or
 * negative for a spectrum not narrowed to a bin: evaluated bin by bin then (per_bin). */
inline VcmF vcm_eval(const SceneView* s, const Surface* surf, float3 ns, float3 nf, float3 wo, float3 wi, float3 other,
                     float eta) {
  VcmF r;
  r.lambert = r.white = r.conductor = r.cos_m = 0.0f;
#if KASHA_TRANSMISSION
  r.through = false;
  if (surf->share_t > 0.0f && dot(ns, wo) * dot(ns, wi) < 0.0f) {
    r.through = true;
    r.lambert = KASHA_INV_PI;
    return r;
  }
#endif
#if KASHA_DISPERSION
  r.per_bin = false;
#endif
#if KASHA_ROUGH
  if (surface_rough(surf)) {
    Frame fr = surface_frame(surf, nf);
    float pdf;
    float3 o = to_local(&fr, wo), i = to_local(&fr, wi);
#if KASHA_CONDUCTOR
    if (surf->kind == KASHA_KIND_CONDUCTOR) {
      r.conductor = conductor_lobe_eval(surf, o, i, &pdf, &r.cos_m);
      return r;
    }
#endif
#if KASHA_DISPERSION
    if (eta < 0.0f) {
      r.per_bin = true;
      r.o = o;
      r.i = i;
      return r;
    }
#endif
#if KASHA_DIELECTRIC
    r.white = rough_dielectric_eval(o, i, eta, surf->alpha, true, &pdf);
#endif
    return r;
  }
#endif
  if (!(dot(ns, wo) > 0.0f && dot(ns, wi) > 0.0f)) return r;
  r.lambert = KASHA_INV_PI * surface_lambert_weight(surf, dot(ns, other));
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    Frame fr = frame_of(ns);
    float pdf;
    r.white = coat_lobe_eval(surf, to_local(&fr, wo), to_local(&fr, wi), &pdf);
    return r;
  }
#endif
#if KASHA_GLOSS
  if (surf->g > 0.0f && !surf->mirror) r.white = surf->g * lobe_brdf(surf->m, s->lobes, wo, wi, ns);
#endif
  return r;
}

/* The index a light vertex's rough dielectric is evaluated at: bin by bin (-1) where it disperses,
 * else its own. */
inline float vcm_light_eta(const Surface* surf) {
#if KASHA_DISPERSION
  if (surf->dispersive) return -1.0f;
#endif
  return surface_eta(surf);
}

/* out = f·phi at a light vertex (vcm_eval's parts applied to the light's spectrum: ρ∘Φ, the
 * re-emission ê (a·Φ), white, a conductor's F(λ)). */
inline void vcm_light_apply(const Surface* surf, VcmF fv, const __global float* phi, __global float* out) {
#if KASHA_DISPERSION
  if (fv.per_bin) {
    float pdf;
    for (int i = 0; i < KASHA_BINS; ++i)
      out[i] = phi[i] == 0.0f ? 0.0f : phi[i] * rough_dielectric_eval(fv.o, fv.i, surf->eta_bins[i], surf->alpha, true, &pdf);
    return;
  }
#endif
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f) {
    for (int i = 0; i < KASHA_BINS; ++i)
      out[i] = phi[i] * fv.conductor * conductor_reflectance(fv.cos_m, surf->eta_c[i], surf->k_c[i], surf->coat_c);
    return;
  }
#endif
  float l = surf->passive ? fv.lambert : 0.0f;
#if KASHA_TRANSMISSION
  if (fv.through) {
    for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * surf->tau[i] * l;
    return;
  }
#endif
#if KASHA_FLUORESCENCE
  float fl = surf->fluorescent ? fv.lambert * spectrum_dot(KASHA_BINS, 0, surf->a, phi) : 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * l + fv.white) + surf->ehat[i] * fl;
#else
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * (surf->rho[i] * l + fv.white);
#endif
}

/* rows += scale · T·f·spectrum at a camera vertex (vcm_eval's parts, next_event.h's terms). */
inline void vcm_camera_apply(const PathWeight* p, const FilmView* f, const Surface* surf, VcmF fv,
                             const __global float* spectrum, float scale, float* rows) {
#if KASHA_CONDUCTOR
  if (fv.conductor > 0.0f) {
    pw_add_conductor(p, f, spectrum, surf->eta_c, surf->k_c, surf->coat_c, fv.cos_m, scale * fv.conductor, rows);
    return;
  }
#endif
  if (fv.lambert > 0.0f) {
#if KASHA_TRANSMISSION
    if (fv.through) {
      pw_add(p, f, surf->tau, spectrum, scale * fv.lambert, rows);
      return;
    }
#endif
    if (surf->passive) pw_add(p, f, surf->rho, spectrum, scale * fv.lambert, rows);
#if KASHA_FLUORESCENCE
    if (surf->fluorescent)
      pw_add(p, f, surf->ehat, 0, scale * fv.lambert * spectrum_dot(KASHA_BINS, 0, surf->a, spectrum), rows);
#endif
  }
  if (fv.white > 0.0f) pw_add(p, f, spectrum, 0, scale * fv.white, rows);
}
