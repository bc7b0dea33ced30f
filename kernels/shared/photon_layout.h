/* Record layouts of photon mapping, shared by host and kernels. Their sizes depend on the bin
 * count N, the film rows R, whether the scene fluoresces and whether it has scattering media
 * (S), so they are float arrays with these strides and offsets rather than structs.
 *
 * Photon: position (3), normal on the side it arrived from (3), its key — the photon's index in
 * the pass and the bounce it was stored at, two ints in float bits, which order a cell's photons
 * so a gather sums them in the same order on any device and in any launch order — then power per
 * bin (N); with scattering media, its direction of travel (3). A photon stored at a collision in
 * a medium has no normal: (0, 0, 0).
 * Visible point: position (3), normal on the camera's side (3), valid flag (under --max-depth: 1 +
 * the bounces the camera path made before it, for the gather's cap), path length from the
 * camera (for the initial radius), then the factor K = C∘d + c bᵀ that maps a photon's power to the
 * pixel's film rows: d (N) and, in a fluorescent scene only, c (R) and b (N); with scattering
 * media, the direction back along the camera path ωo (3) and the phase function's g (1). A
 * visible point at a collision in a medium has no normal: (0, 0, 0). */
#ifndef KASHA_PHOTON_LAYOUT_H
#define KASHA_PHOTON_LAYOUT_H

/* A gather counts photons only within this fraction of its radius of the visible point's tangent
 * plane (the host's and the device's gathers alike). */
#define KASHA_GATHER_SLAB 0.25f

#define KASHA_PHOTON_FLOATS(N, S) (8 + (N) + ((S) ? 3 : 0))
#define KASHA_PHOTON_INDEX 6
#define KASHA_PHOTON_DEPTH 7
#define KASHA_PHOTON_POWER 8
#define KASHA_PHOTON_DIRECTION(N) (8 + (N))

#define KASHA_VP_VALID 6
#define KASHA_VP_DISTANCE 7
#define KASHA_VP_D 8
#define KASHA_VP_C(N) (8 + (N))
#define KASHA_VP_B(N, R) (8 + (N) + (R))
#define KASHA_VP_WO(N, R, FLUORESCENT) (8 + (N) + ((FLUORESCENT) ? (R) + (N) : 0))
#define KASHA_VP_G(N, R, FLUORESCENT) (KASHA_VP_WO(N, R, FLUORESCENT) + 3)
#define KASHA_VP_FLOATS(N, R, FLUORESCENT, S) (KASHA_VP_WO(N, R, FLUORESCENT) + ((S) ? 4 : 0))

#endif
