/* PCG32 (O'Neill 2014): one independent stream per work item, seeded from (seed, pass, item) so
 * results do not depend on the work-group size or the order work items run in. */
#ifndef KASHA_RNG_H
#define KASHA_RNG_H

typedef struct {
  ulong state;
  ulong inc;
} Rng;

inline uint rng_next_uint(Rng* r) {
  ulong old = r->state;
  r->state = old * 6364136223846793005UL + r->inc;
  uint xorshifted = (uint)(((old >> 18u) ^ old) >> 27u);
  uint rot = (uint)(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

/* Uniform in [0, 1). */
inline float rng_next_float(Rng* r) { return (float)(rng_next_uint(r) >> 8) * (1.0f / 16777216.0f); }

/* Two and three numbers in a fixed order (function arguments are evaluated in none). */
inline float2 rng_next_float2(Rng* r) {
  float a = rng_next_float(r);
  float b = rng_next_float(r);
  return (float2)(a, b);
}
inline float3 rng_next_float3(Rng* r) {
  float2 ab = rng_next_float2(r);
  float c = rng_next_float(r);
  return (float3)(ab.x, ab.y, c);
}

inline Rng rng_seed(uint seed, uint pass, uint item) {
  Rng r;
  r.state = 0UL;
  r.inc = ((((ulong)seed << 32) ^ (ulong)item) << 1u) | 1u;
  rng_next_uint(&r);
  r.state += ((ulong)pass << 32) ^ (ulong)item * 0x9E3779B97F4A7C15UL;
  rng_next_uint(&r);
  return r;
}

#endif
