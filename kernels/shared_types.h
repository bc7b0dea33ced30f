/* Struct layouts shared by the host (C++) and the kernels (OpenCL C): each layout exists once, here.
 * Only 4-byte scalars and arrays of them, so both compilers lay them out identically without
 * the 16-byte alignment that float3 has in OpenCL. */
#ifndef KASHA_SHARED_TYPES_H
#define KASHA_SHARED_TYPES_H

#ifndef __OPENCL_VERSION__
#include <cstdint>
namespace kasha {
typedef std::uint32_t uint;
#define KASHA_STATIC_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T " layout changed")
/* Headers that host and kernels share: global pointers are plain pointers on the host, and sums
 * are carried in double there. */
#define KASHA_GLOBAL
typedef double kasha_real;
#else
#define KASHA_STATIC_SIZE(T, bytes)
#define KASHA_GLOBAL __global
typedef float kasha_real;
#endif

/* The deepest BVH the builder may make; the traversal's stack holds one node per level. */
#define KASHA_BVH_MAX_DEPTH 64

/* Next-event estimation samples a triangle by solid angle between these (steradians), by area
 * outside: below, Arvo's construction in float lands points up to 1e-4 (barycentric) off small
 * triangles on some devices (seen at 1.3e-3 sr on an NVIDIA H100) while area sampling is as good
 * there; above, the triangle nearly fills the hemisphere (pbrt-v4's bound). */
#define KASHA_MIN_SPHERICAL_SOLID_ANGLE 1e-2f
#define KASHA_MAX_SPHERICAL_SOLID_ANGLE 6.22f

/* A guard on path length in every kernel, far beyond what Russian roulette reaches (a path of a
 * scene keeping 99.99 % of its light passes it with probability e^-26); what it cuts is counted
 * and reported. Kernels are built with the render's --max-depth in its place. */
#ifndef KASHA_MAX_PATH_DEPTH
#define KASHA_MAX_PATH_DEPTH (1 << 18)
#endif

/* One node of the flattened binary BVH, in depth-first order. Interior: count == 0, the left child
 * is the next node and `offset` is the right child. Leaf: triangles [offset, offset + count). */
typedef struct {
  float lo[3];
  int offset;
  float hi[3];
  int count;
} KBvhNode;
KASHA_STATIC_SIZE(KBvhNode, 32);

/* A triangle in BVH leaf order. `prim` is its index in scene order (what Embree reports as primID);
 * `emitter` indexes the emitter table, -1 when the triangle does not emit. */
typedef struct {
  float v0[3];
  float v1[3];
  float v2[3];
  int material;
  int emitter;
  int prim;
} KTriangle;
KASHA_STATIC_SIZE(KTriangle, 48);

/* A ray segment [tmin, tmax]. */
typedef struct {
  float org[3];
  float tmin;
  float dir[3];
  float tmax;
} KRay;
KASHA_STATIC_SIZE(KRay, 32);

/* Closest hit: prim == -1 for a miss; (u, v) are barycentrics of v1 and v2. */
typedef struct {
  float t;
  int prim;
  float u;
  float v;
} KHit;
KASHA_STATIC_SIZE(KHit, 16);

/* Pinhole camera: a pixel (px, py), row 0 at the top, looks along
 * forward + (2 (px + 0.5) / width - 1) * right_scaled + (1 - 2 (py + 0.5) / height) * up_scaled. */
typedef struct {
  float position[3];
  int width;
  float forward[3];
  int height;
  float right[3]; /* already scaled by tan(fov/2) and the aspect ratio */
  float pad0;
  float up[3]; /* already scaled by tan(fov/2) */
  float pad1;
} KCamera;
KASHA_STATIC_SIZE(KCamera, 64);

/* Per-material data the kernels read; spectra live in one float buffer at the given offsets
 * (N values each, -1 when the part is absent; the buffer starts with N zeros that kernels read
 * in place of an absent part). */
typedef struct {
  int passive;    /* rho(lambda) */
  int excitation; /* a(lambda) */
  int emission;   /* e_hat = e * bin width, sums to 1 */
  int lobe;       /* gloss lobe table (KASHA_LOBE_CELLS pdf values then as many CDF values), -1: mirror */
  float gloss;    /* g; 0 without a gloss part */
  float cone_rad; /* half-angle of the gloss cone */
  float excitation_sum; /* sum_i a_i, for the branch probabilities */
  float pad0;
  float albedo_xyz[3]; /* colour under equal-energy light, fluorescence included (debug view) */
  int flags;
} KMaterial;
KASHA_STATIC_SIZE(KMaterial, 48);

/* Gloss lobes are tabulated in this many equal rings of angle from the mirror direction. */
#define KASHA_LOBE_CELLS 64

#ifndef __OPENCL_VERSION__
}  // namespace kasha
#endif

#endif
