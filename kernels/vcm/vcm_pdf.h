/* The pseudo-densities the MIS weights use (SmallVCM's BSDF Pdf): functions of the material and
 * the two directions alone, so both subpaths evaluate them alike. */

/* A vertex connects where its surface has a non-delta part: a Lambert part (bare or under a
 * coat), a tabulated gloss lobe, a rough coat's lobe, or a rough dielectric or conductor. It
 * merges where it has a Lambert part or a tabulated lobe: a rough interface only connects, a
 * choice both subpaths make alike from the material (the recursion leaves its merge out); ppm
 * merges at a rough conductor too. */
inline bool vcm_connectible(const Surface* surf) {
  if (surface_rough(surf)) return true;
  if (surface_specular(surf)) return false;
  return surface_has_lambert(surf) || (surf->g > 0.0f && !surf->mirror);
}
inline bool vcm_mergeable(const Surface* surf) {
#if KASHA_CONDUCTOR
  /* ppm, merges alone, must merge at a rough conductor: else a delta light's reflection in it
   * (a sun, a spot) would reach the camera by no technique. */
  if (!KASHA_VCM_CONNECT && surface_rough(surf) && surf->kind == KASHA_KIND_CONDUCTOR) return true;
#endif
  if (surface_specular(surf)) return false;
  return surface_has_lambert(surf) || (surf->g > 0.0f && !surf->mirror);
}

/* The Lambert parts' mean reflectance and excitation (after textures and a coat's series), from
 * the material alone: what the pseudo-density mixes the gloss part against. */
inline float vcm_lambert_mean(const Surface* surf) {
  float lambert = 0.0f;
  if (surf->passive)
    for (int i = 0; i < KASHA_BINS; ++i) lambert += surf->rho[i];
#if KASHA_TRANSMISSION
  if (surf->share_t > 0.0f)
    for (int i = 0; i < KASHA_BINS; ++i) lambert += surf->tau[i];
#endif
#if KASHA_FLUORESCENCE
  if (surf->fluorescent) lambert += surf->a_sum;
#endif
  return lambert / KASHA_BINS;
}

/* The gloss part's share of the pseudo-density for a subpath that met the vertex at |cos| mu:
 * g against the Lambert parts' mean, for a coat both taken at mu (its Fresnel reflectance or
 * rough lobe albedo, and t(mu) for the parts under it); a function of the material and mu alone,
 * so both subpaths find the same density for the same pair of directions. */
inline float vcm_share(const Surface* surf, float lambert, float mu) {
#if KASHA_COATED
  if (surf->coated) {
    float g = (coat_rough(surf) ? coat_table_at(surf, 0, mu) : fresnel_dielectric(mu, surf->m->coat_eta)) *
              surf->m->layer_scale;
    float l = lambert * coat_transmission(surf, mu) * surf->m->coat_albedo;
    return g + l > 0.0f ? g / (g + l) : 0.0f;
  }
#endif
  if (!(surf->g > 0.0f)) return 0.0f;
  return surf->g / (surf->g + lambert);
}

/* The pseudo-density (per solid angle) of leaving the vertex along `to` having arrived from
 * `from` (both pointing away from the surface; ns the normal on from's side, nf the front one):
 * a rough interface's own density (at the material's index); else the Lambert parts' cosine and
 * the tabulated or coat lobe, mixed by the gloss share. A delta part is not in it. */
inline float vcm_pdf(const SceneView* s, const Surface* surf, float lambert, float3 ns, float3 nf, float3 from,
                     float3 to) {
#if KASHA_ROUGH
  if (surface_rough(surf)) {
    Frame fr = surface_frame(surf, nf);
    float pdf, cos_m;
    float3 wo = to_local(&fr, from), wi = to_local(&fr, to);
#if KASHA_DIELECTRIC
    if (surf->kind == KASHA_KIND_DIELECTRIC) {
      rough_dielectric_eval(wo, wi, surf->eta, surf->alpha, true, &pdf);
      return pdf;
    }
#endif
    conductor_lobe_eval(surf, wo, wi, &pdf, &cos_m);
    return pdf;
  }
#endif
  float c = dot(ns, to);
#if KASHA_TRANSMISSION
  /* A transmitting surface (no other part): the passive part's cosine on either side, by the
   * material's share of each (surface.h); ns may lie on either direction's side. */
  if (surf->share_t > 0.0f) return fabs(c) * KASHA_INV_PI * surface_side_share(surf, c * dot(ns, from) < 0.0f);
#endif
  if (c <= 0.0f) return 0.0f;
  float share = vcm_share(surf, lambert, dot(ns, from));
  float pdf = (1.0f - share) * c * KASHA_INV_PI;
#if KASHA_COATED
  if (surface_coat_lobe(surf)) {
    Frame fr = frame_of(ns);
    float lobe;
    coat_lobe_eval(surf, to_local(&fr, from), to_local(&fr, to), &lobe);
    return pdf + share * lobe;
  }
#endif
#if KASHA_GLOSS
  if (share > 0.0f && !surf->mirror) pdf += share * lobe_pdf(surf->m, s->lobes, dot(to, reflect_dir(-from, ns)));
#endif
  return pdf;
}
