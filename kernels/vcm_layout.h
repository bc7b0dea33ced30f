/* The light-vertex record of vertex connection and merging (vcm.cl), shared by host and kernels:
 * a photon record (photon_layout.h: position, geometric normal on the side the light arrived
 * from, key, power per bin with the arrival half of the shading-normal correction), then what connections and Georgiev's MIS recursion need — the direction the
 * light travelled to arrive, the partial weights dVCM, dVC and dVM, the triangle (leaf order), the
 * hit's offset, the record of the light path's previous stored vertex (-1: none), so that a camera
 * path walks its light path's vertices from the last stored one back, its ordinal among them (0
 * for the first stored), the hit's barycentrics (for textures), whether merges may use it (1; 0
 * at a rough interface, which only connects, and with caustic merges where the light came by no
 * delta bounce) and the shading normal on the light's side. */
#ifndef KASHA_VCM_LAYOUT_H
#define KASHA_VCM_LAYOUT_H

#include "photon_layout.h"

#define KASHA_VCM_ARRIVAL(N) (KASHA_PHOTON_FLOATS(N))
#define KASHA_VCM_DVCM(N) (KASHA_PHOTON_FLOATS(N) + 3)
#define KASHA_VCM_DVC(N) (KASHA_PHOTON_FLOATS(N) + 4)
#define KASHA_VCM_DVM(N) (KASHA_PHOTON_FLOATS(N) + 5)
#define KASHA_VCM_TRIANGLE(N) (KASHA_PHOTON_FLOATS(N) + 6)
#define KASHA_VCM_EPS(N) (KASHA_PHOTON_FLOATS(N) + 7)
#define KASHA_VCM_PREVIOUS(N) (KASHA_PHOTON_FLOATS(N) + 8)
#define KASHA_VCM_ORDINAL(N) (KASHA_PHOTON_FLOATS(N) + 9)
#define KASHA_VCM_BARYCENTRICS(N) (KASHA_PHOTON_FLOATS(N) + 10)
#define KASHA_VCM_MERGEABLE(N) (KASHA_PHOTON_FLOATS(N) + 12)
#define KASHA_VCM_SHADING(N) (KASHA_PHOTON_FLOATS(N) + 13)
#define KASHA_VCM_FLOATS(N) (KASHA_PHOTON_FLOATS(N) + 16)

#endif
