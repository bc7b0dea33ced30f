/* vcm's modes and test hooks, as build options (host/integrators/vcm/vcm_integrator.cpp sets
 * them), and the MIS factors every technique weighs by. Modes are used as constant `if`s where
 * the code compiles in every mode; #if only where a mode removes a buffer (the grid in bpt). */
#ifndef KASHA_VCM_CONNECT
#define KASHA_VCM_CONNECT 1
#endif
#ifndef KASHA_VCM_MERGE
#define KASHA_VCM_MERGE 1
#endif
/* Where vcm merges (--merges): at every camera vertex that is not delta (1, Georgiev et al.), or
 * only at the first (0, as SPPM gathers; the default, with caustic merges below): then no light
 * vertex but one the camera sees directly is a merging vertex of any full path — the light subpaths' partial weights leave
 * their own merges out, light tracing keeps the merge at the vertex it splats, and a connection
 * counts no merge on the light side — so every path still has its weights summing to one, and a
 * camera path makes one range query instead of one a bounce. */
#ifndef KASHA_VCM_MERGE_EVERY
#define KASHA_VCM_MERGE_EVERY 0
#endif
/* --merges caustic (the default but in caustic-lit views, host/integrators/vcm/vcm_integrator.cpp;
 * with merges at the first vertex): a merge counts only for a path
 * whose light arrived at the merging vertex from a delta bounce (a mirror, glass: a caustic), the
 * paths no connection and no next-event estimation reaches. Elsewhere connections do better than
 * a count of photons in a disc, and a merge there costs a range query for almost no weight; so
 * the grid holds only the light vertices reached from a delta bounce (none on a diffuse scene).
 * Every technique knows whether the path it makes is such: a light subpath from its last bounce;
 * a camera path from the bounce after its merging vertex (the part of dVC that merge put in is
 * kept apart until then, VcmCamera), so every path's weights still sum to one. */
#ifndef KASHA_VCM_MERGE_CAUSTIC
#define KASHA_VCM_MERGE_CAUSTIC 0
#endif

/* Floats of a work item's spectra: a light vertex's f·Φ, then room for the light vertex's
 * surface (textured, coated) apart from the camera vertex's in the scene's scratch. */
#define VCM_SPECTRA (KASHA_BINS + KASHA_SCRATCH_FLOATS)

/* Test hooks (tests/vcm_test.cpp): KASHA_VCM_LENGTH > 0 keeps only the contributions of paths of
 * that many segments; KASHA_VCM_EMISSION_ONLY keeps only camera paths hitting emitters,
 * unweighted (path tracing without next-event estimation: the plain estimate the weighted
 * techniques must add up to); KASHA_VCM_DROP_DENSITY leaves next-event estimation's density out
 * of light tracing's weight, a wrong weight the tests must catch. */
#ifndef KASHA_VCM_LENGTH
#define KASHA_VCM_LENGTH 0
#endif
#ifndef KASHA_VCM_EMISSION_ONLY
#define KASHA_VCM_EMISSION_ONLY 0
#endif
#ifndef KASHA_VCM_DROP_DENSITY
#define KASHA_VCM_DROP_DENSITY 0
#endif
/* A path of `segments` segments has segments − 1 scattering vertices, which --max-depth's cap
 * (KASHA_DEPTH_CAP, shared_types.h) bounds; every technique of a path sees the same count, so its
 * weights still sum to one. */
#ifdef KASHA_DEPTH_CAP
#define VCM_LENGTH_COUNTS(segments) \
  ((KASHA_VCM_LENGTH == 0 || (segments) == KASHA_VCM_LENGTH) && (segments) <= KASHA_DEPTH_CAP + 1)
#else
#define VCM_LENGTH_COUNTS(segments) (KASHA_VCM_LENGTH == 0 || (segments) == KASHA_VCM_LENGTH)
#endif

/* The MIS factors of an iteration with merging radius r and L light subpaths, η = κ π r² L / spp
 * (SmallVCM's mMisVmWeightFactor and mMisVcWeightFactor): a merge weighs η against a
 * connection's 1, a connection 1/η against a merge; 0 for a technique the mode leaves out. */
inline float vcm_merge_factor(float eta) { return KASHA_VCM_MERGE ? eta : 0.0f; }
inline float vcm_connect_factor(float eta) { return KASHA_VCM_CONNECT ? 1.0f / eta : 0.0f; }

/* Light tracing's share ν: the weights count light tracing as ν·L samples of a pixel against its
 * spp camera paths (SmallVCM counts L). The balance heuristic assumes independent samples, but a
 * pixel's camera paths are Owen-scrambled Sobol points — stratified over the pixel, the first
 * bounces and next-event estimation's light points — while the splats that land in a pixel are
 * not, so at equal count the camera side is far less noisy (backward's RMSE on the torus after
 * 20 s: 3.55 with Sobol, 8.72 with independent samples). ν = 1/10 with Sobol, 1 with
 * --sampler independent, where the heuristic's assumption holds (docs/integrators.md). Light
 * tracing keeps the whole weight where no camera technique reaches a path; both subpaths use the
 * same ν, so every path's weights still sum to one. */
#define KASHA_VCM_TRACING_SHARE (KASHA_SOBOL ? 0.1f : 1.0f)

/* The merging radius where a camera path that travelled `travelled` merges (KVcmRadius,
 * vcm_records.h). Either subpath finds the radius of a vertex where the camera path would merge
 * (light tracing: its distance to the camera), so both weigh merges alike. */
inline float vcm_radius_at(const KVcmRadius* r, float travelled) {
  return r->per_unit > 0.0f ? fmin(r->per_unit * travelled, r->radius) : r->radius;
}
inline float vcm_eta_at(const KVcmRadius* r, float radius) { return r->eta_unit * radius * radius; }

/* Stored light vertex `slot` of the store (vcm_records.h), and its power per bin after it. */
inline const __global KVcmLightVertex* vcm_vertex(const __global float* store, int slot) {
  return (const __global KVcmLightVertex*)(store + (long)slot * VCM_FLOATS);
}
inline const __global float* vcm_vertex_power(const __global KVcmLightVertex* v) {
  return (const __global float*)(v + 1);
}
