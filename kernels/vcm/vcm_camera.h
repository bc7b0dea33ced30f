/* A camera subpath's state (SmallVCM's SubPathState for the camera side) and what a camera pass
 * gives each of its paths. */

/* The hashed grid over the store's mergeable vertices (hash_grid.cl), in the merging modes. Once
 * built, cell h's run ends at cell_end[h] and starts where cell h - 1's ends (a prefix sum over
 * the cells in hash order), so its counts are not needed. */
typedef struct {
  const __global float4* placed; /* per grid slot: the vertex's position and record */
  const __global int* cell_end;
} VcmGrid;

/* What a camera path takes from its launch: the iteration, the store of light vertices and its
 * chunk's subpaths, the grid, the work item's spectra (VCM_SPECTRA floats), and its light subpath
 * `partner` — `own`: in the store's chunk (emission, next-event estimation and connections count
 * then; merges count with every chunk); `seen_apart`: vcm_seen_light takes the light reached
 * through delta bounces alone, so the path leaves it out. */
typedef struct {
  const KVcmIteration* it;
  const __global float* store;
  const __global KVcmLightPath* light_paths;
  const VcmGrid* grid;
  __global float* out;
  int partner;
  bool own, seen_apart;
} VcmCameraInputs;

/* A camera subpath: the walk (camera_walk.h) and its partial MIS weights; dvc_merge, the part of
 * dVC the merge at its merging vertex put in, until the next vertex's bounce decides whether that
 * merge makes the paths beyond (caustic merges: if that bounce is delta). */
typedef struct {
  CameraWalk w;
  float dvcm, dvc, dvm, dvc_merge;
#if KASHA_SCATTERING
  float sigma_prev; /* σ̄ where the segment now flown started (1: a surface or the camera) */
#endif
} VcmCamera;

/* The camera's density of the direction `dir` per solid angle, for one of the pixel's spp samples:
 * a camera path's dVCM at its start (light subpaths over camera paths, as SmallVCM's with one
 * camera path a pixel). */
inline void vcm_camera_start(const SceneView* s, float3 dir, float paths, int spp, VcmCamera* c) {
  const KCamera* k = &s->camera;
  float share = KASHA_VCM_TRACING_SHARE * paths / spp;
  if (k->type == KASHA_CAMERA_PERSPECTIVE) { /* camera_pixel_solid_angle's, in the order it had */
    float cos_c = dot(dir, normalize(camera_vec(k->forward)));
    c->dvcm = share * camera_pixel_area(k) * cos_c * cos_c * cos_c;
  } else {
    c->dvcm = share * camera_pixel_solid_angle(k, dir);
  }
  c->dvc = c->dvm = c->dvc_merge = 0.0f;
#if KASHA_SCATTERING
  c->sigma_prev = 1.0f;
#endif
}

/* dVC for the techniques at the current vertex (next-event estimation, connections, an emitter
 * hit): with caustic merges, at the vertex after the merging one no merge makes their paths (the
 * light reaches the merging vertex from this vertex's own non-delta scattering or emission). */
inline float vcm_camera_dvc(const VcmCamera* c) {
  return KASHA_VCM_MERGE_CAUSTIC ? fmax(c->dvc - c->dvc_merge, 0.0f) : c->dvc;
}

/* Caustic merges: the vertex after the merging one scatters (delta or not): the merge's part of
 * dVC stays for the paths beyond only if it is delta. */
inline void vcm_camera_decide(VcmCamera* c, bool delta) {
  if (KASHA_VCM_MERGE_CAUSTIC && c->dvc_merge > 0.0f && !delta) c->dvc = fmax(c->dvc - c->dvc_merge, 0.0f);
  c->dvc_merge = 0.0f;
}

/* What a camera vertex's techniques share: its normals (densities and f about the shading
 * normal, turns to area about the geometric one), the Lambert mean its pseudo-densities
 * mix by, and whether it merges. */
typedef struct {
  float3 ns, nf, ng; /* shading normal on the eye's side, on the front; geometric on the eye's side */
  float lambert;
  float eta; /* a rough dielectric's index for the path (at its bin where it disperses) */
  bool merges;
  int medium; /* a collision in this medium (vcm_media.h; no surface, normals unset), -1: a surface */
  float sparse; /* at a collision, 1 / its medium's density there (medium_inverse_density) */
} VcmVertex;

/* The MIS factors at a camera vertex, its merges' radius's (vcm_merge_factor, vcm_connect_factor):
 * a surface's by the disc, a collision's by the sphere (vcm_volume_eta; scattering scenes only). */
typedef struct {
  float vm, vc, vm_volume, vc_volume;
} VcmFactors;

inline VcmFactors vcm_factors(const KVcmRadius* radius, float r) {
  VcmFactors k;
  k.vm = vcm_merge_factor(vcm_eta_at(radius, r));
  k.vc = vcm_connect_factor(vcm_eta_at(radius, r));
#if KASHA_SCATTERING
  k.vm_volume = vcm_merge_factor(vcm_volume_eta(radius, r));
  k.vc_volume = vcm_connect_factor(vcm_volume_eta(radius, r));
#else
  k.vm_volume = k.vc_volume = 0.0f;
#endif
  return k;
}
