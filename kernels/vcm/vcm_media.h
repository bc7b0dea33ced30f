/* vcm, bpt and ppm in scattering media (docs/media.md#vcm-bpt-and-ppm-in-scattering-media): the point–point
 * subset of Křivánek et al. 2014 ("Unifying points, beams and paths in volumetric light transport
 * simulation"). A collision in a medium is a vertex as a surface hit is: the light pass stores
 * it (KASHA_VCM_MEDIUM) and splats it to the camera; a camera path's collision takes next-event
 * estimation, connects to its light subpath's vertices (surface or medium) and merges with the
 * stored collisions within r in 3-D (a surface vertex merges only with surface ones). Its measure
 * is volume, not area: no cosine turns a density to it, and a merge's kernel is the sphere's
 * (4/3)πr³, so its η is κ (4/3)πr³ L / spp in place of the disc's κ πr² L / spp.
 *
 * The free flight's densities join the weights. vcm's weights use pseudo-densities both subpaths
 * evaluate alike (vcm.cl); a flight's is T̄·σ̄ to a collision and T̄ to a surface, T̄ the mean over the
 * bins of the segment's transmittance and σ̄ the medium's mean extinction (KMedium.sigma_mean);
 * a collision's direction density is the phase function and isotropic re-emission mixed by the
 * medium's elastic share. Each contribution still divides by the density it was truly drawn with
 * (medium_flight.h's mixture over the bins), so connections stay unbiased and merges consistent.
 * In the recursion a segment's T̄ cancels between its forward density and its reverse one (both
 * cross it), leaving σ̄(previous)/σ̄(here) in dVC and dVM and 1/(T̄ σ̄(here)) in dVCM; a segment no
 * subpath sampled (a connection, next-event estimation, light tracing's) puts its T̄ σ̄ in the
 * weight of each technique that would have sampled it. */

#if KASHA_SCATTERING
/* T̄ of a connection whose transmittance segment_clear gave (null: no medium on the way). */
inline float vcm_segment_mean(const __global float* tr) {
  if (!tr) return 1.0f;
  float sum = 0.0f;
  for (int i = 0; i < KASHA_BINS; ++i) sum += tr[i];
  return sum / KASHA_BINS;
}

/* The pseudo-density (per solid angle) of leaving a collision in m along `to` having arrived from
 * `from` (both pointing away from it): symmetric in the two. */
inline float vcm_medium_pdf(const __global KMedium* m, float3 from, float3 to) {
  return m->elastic_share * hg_phase(dot(from, to), m->g) + (1.0f - m->elastic_share) * KASHA_INV_4PI;
}

/* A merge's η in a medium at radius r: the sphere's volume in place of the disc's area. */
inline float vcm_volume_eta(const KVcmRadius* r, float radius) {
  return vcm_eta_at(r, radius) * (4.0f / 3.0f) * radius;
}

/* After vcm_arrived (at cos_in 1 for a collision): the flight's pseudo-densities, T̄ over the
 * segment, σ̄ at its start (1 at a surface or a light) and at its end. */
inline void vcm_through(float tbar, float sigma_prev, float sigma_here, float* dvcm, float* dvc, float* dvm,
                        float* dvc_merge) {
  *dvcm /= tbar * sigma_here;
  float k = sigma_prev / sigma_here;
  *dvc *= k;
  *dvm *= k;
  *dvc_merge *= k;
}

/* out = f·Φ at a light vertex at x in medium m, the light having arrived from `light` and leaving
 * along `to` (both away from it): Φ∘σs times the phase function, and each dye's ê Φ_d (a·Φ)/4π.
 * A component grid's σs at x goes to scratch slot 1: slot 0 holds the camera vertex's. */
inline void vcm_medium_light_apply(const SceneView* s, const __global KMedium* m, float3 x,
                                   float3 light, float3 to, const __global float* phi,
                                   __global float* out) {
  float phase = hg_phase(dot(light, to), m->g);
  const __global float* sigma_s = s->spectra + m->sigma_s;
#if KASHA_GRID_COMPONENTS
  if (m->components > 0) sigma_s = components_at(s, m, x, 1) + KASHA_BINS;
#endif
  for (int i = 0; i < KASHA_BINS; ++i) out[i] = phi[i] * sigma_s[i] * phase;
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) {
    const __global KFluorophore* fl = &m->fluorophore[k];
    float emitted = fl->yield * spectrum_dot(KASHA_BINS, 0, s->spectra + fl->absorption, phi) * KASHA_INV_4PI;
    const __global float* e = s->spectra + fl->emission;
    for (int i = 0; i < KASHA_BINS; ++i) out[i] += e[i] * emitted;
  }
#endif
}

/* rows += scale · T·f·spectrum at a camera path's collision in m, the eye along `eye` and the light
 * arriving from `light`: σs and the phase function, and each dye's ê Φ_d (a·spectrum)/4π. */
inline void vcm_medium_camera_apply(const PathWeight* p, const SceneView* s, const FilmView* f,
                                    const __global KMedium* m, float3 eye, float3 light,
                                    const __global float* spectrum, float scale, float* rows) {
  pw_add(p, f, medium_scattering(s, m), spectrum, scale * hg_phase(dot(eye, light), m->g), rows);
#if KASHA_FLUORESCENCE
  for (int k = 0; k < m->fluorophores; ++k) {
    const __global KFluorophore* fl = &m->fluorophore[k];
    float absorbed = fl->yield * spectrum_dot(KASHA_BINS, 0, s->spectra + fl->absorption, spectrum);
    pw_add(p, f, s->spectra + fl->emission, 0, scale * absorbed * KASHA_INV_4PI, rows);
  }
#endif
}
#endif

/* T̄ for the weights of a technique over a segment that no subpath sampled: 1 without scattering
 * media, where no density depends on it. */
inline float vcm_unsampled(const __global float* tr) {
#if KASHA_SCATTERING
  return vcm_segment_mean(tr);
#else
  return 1.0f;
#endif
}
