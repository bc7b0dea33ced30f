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

/* splitmix64's finalizer: nearby inputs give unrelated outputs. */
inline ulong mix64(ulong z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9UL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebUL;
  return z ^ (z >> 31);
}

/* State and increment both hashed from (seed, pass, item), so neighbouring items' streams are
 * unrelated (increments that differ in one bit give correlated PCG streams). */
inline Rng rng_seed(uint seed, uint pass, uint item) {
  ulong key = mix64(((ulong)seed << 32 | pass) + 0x9e3779b97f4a7c15UL);
  Rng r;
  r.state = 0UL;
  r.inc = (mix64(key ^ item) << 1) | 1UL;
  rng_next_uint(&r);
  r.state += mix64(key + 0x632be59bd9b4e019UL * ((ulong)item + 1UL));
  rng_next_uint(&r);
  return r;
}

#endif
