/* What one launch of each integrator's kernels takes besides the scene, the film and its buffers,
 * shared by the host and the kernels (vcm's are kernels/shared/vcm_records.h): one record a launch
 * instead of positional scalars, each field named. 4-byte fields only (shared_types.h's rule). */
#ifndef KASHA_LAUNCH_RECORDS_H
#define KASHA_LAUNCH_RECORDS_H

#include "shared/shared_types.h"

#ifndef __OPENCL_VERSION__
namespace kasha {
#endif

/* render_backward (backward.cl): this launch renders samples [k_first, k_last) of each pixel's
 * spp. */
typedef struct {
  int spp, k_first, k_last;
  uint seed, pass;
} KBackwardLaunch;
KASHA_STATIC_SIZE(KBackwardLaunch, 20);

/* trace_forward (forward.cl): `photons` a pass, photons_per_item a work item, the path-length
 * guard, the fixed-point film's scale (fixed_point_film.h). */
typedef struct {
  int photons, photons_per_item, max_depth, film_shift;
  uint seed, pass;
} KForwardLaunch;
KASHA_STATIC_SIZE(KForwardLaunch, 24);

/* trace_photon_map (photon_map.cl): photons [first_photon, first_photon + count) of the pass's
 * `photons`, photons_per_item a work item, `skip` of its stores passed over (a photon traced again in segments), into a
 * store of `capacity` records. */
typedef struct {
  int photons, first_photon, count, photons_per_item, skip, capacity;
  uint seed, pass;
} KPhotonTraceLaunch;
KASHA_STATIC_SIZE(KPhotonTraceLaunch, 32);

/* camera_pass (photon_map.cl): the first SPPM radius (0: from the footprint), a pixel's footprint
 * per unit distance, the largest radius (render/merge_radius.h), camera paths a pixel. */
typedef struct {
  float radius0, footprint, max_radius;
  int spp;
  uint seed, pass;
} KPhotonCameraLaunch;
KASHA_STATIC_SIZE(KPhotonCameraLaunch, 24);

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
