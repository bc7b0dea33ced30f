/* Sample values for every sampled dimension (docs/design.md#samples). With KASHA_SOBOL (the default,
 * `--sampler sobol`) they come from Owen-scrambled Sobol points (Burley 2020, "Practical hash-based
 * Owen scrambling"): each dimension pair is the (0,2)-sequence of Sobol dimensions 0 and 1 with a
 * nested-uniform shuffle of the sample index and a nested-uniform scramble of each coordinate, all
 * seeded by a hash of (seed, stream, pair). A stream is a pixel (camera paths: index = the pixel's
 * sample number over all passes, so pass k continues pass k − 1 and every prefix of 2^m samples
 * stays stratified) or the photons (index = the photon's number over all passes, a new stream every
 * 2^32 photons).
 * Pixels get independent scrambles, so they stay independent estimates. Everything is integer
 * hashing of (seed, stream, index, pair): the same numbers on any device or process.
 * `--sampler independent` (KASHA_SOBOL 0) draws PCG32 numbers from one stream per work item. */
#ifndef KASHA_SAMPLER_H
#define KASHA_SAMPLER_H

#include "sampling/rng.h"

#ifndef KASHA_SOBOL
#define KASHA_SOBOL 1
#endif

/* lowbias32 (Wellons): a fast integer hash with good avalanche. */
inline uint hash_u32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
inline uint hash_combine(uint seed, uint v) { return hash_u32(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2))); }

inline uint reverse_bits_u32(uint x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

/* Burley's Laine–Karras-style permutation: each bit is flipped by a hash of the bits below it. */
inline uint lk_permutation(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

/* Owen (nested uniform) scrambling of a 32-bit fixed-point value: bit k flipped by a hash of the
 * bits above it. Applied to an index it permutes indices within aligned power-of-two blocks. */
inline uint nested_uniform_scramble(uint x, uint seed) {
  return reverse_bits_u32(lk_permutation(reverse_bits_u32(x), seed));
}

/* Sobol dimension 1 before its bits are reversed: its generator matrix is Pascal's triangle mod 2,
 * so output bit i is the parity of the index bits j ⊇ i (Lucas), a superset transform over the
 * five bits of a bit position: five shift-mask-xor steps instead of a loop over 32 bits. */
inline uint sobol_dimension1_reversed(uint index) {
  index ^= (index >> 1) & 0x55555555u;
  index ^= (index >> 2) & 0x33333333u;
  index ^= (index >> 4) & 0x0f0f0f0fu;
  index ^= (index >> 8) & 0x00ff00ffu;
  index ^= (index >> 16) & 0x0000ffffu;
  return index;
}

/* Dimensions 0 (van der Corput: the reversed index) and 1 of Sobol's sequence, each Owen-scrambled,
 * at a shuffled index. Owen scrambling of a reversed-bits value v is reverse(LK(reverse(v))), so a
 * coordinate whose reversed bits are at hand costs one reversal. */
inline float2 scrambled_sobol_2d(uint index, uint seed) {
  index = nested_uniform_scramble(index, seed);
  uint x = reverse_bits_u32(lk_permutation(index, hash_combine(seed, 1u)));
  uint y = reverse_bits_u32(lk_permutation(sobol_dimension1_reversed(index), hash_combine(seed, 2u)));
  /* 24 bits, so the float is exactly representable and below 1. */
  return (float2)((float)(x >> 8), (float)(y >> 8)) * (1.0f / 16777216.0f);
}

typedef struct {
#if KASHA_SOBOL
  uint key;   /* hash of (seed, stream) */
  uint index; /* the sample's number in its stream */
  uint pair;  /* the next dimension pair */
#else
  Rng rng;
  uint seed, item; /* a pixel's samples reseed from (seed, sample, item): launches may split them */
#endif
} Sampler;

/* `stream`: a pixel, or 0 for a pass's photons; `index`: the sample's number in that stream over
 * all passes; `pass` and `item` seed the independent sampler's PCG stream. */
inline Sampler sampler_start(uint seed, uint stream, uint index, uint pass, uint item) {
  Sampler s;
#if KASHA_SOBOL
  s.key = hash_combine(hash_u32(seed), stream);
  s.index = index;
  s.pair = 0;
#else
  s.rng = rng_seed(seed, pass, item);
  s.seed = seed;
  s.item = item;
#endif
  return s;
}

/* The sampler of photon `index` of pass `pass`: its number over all passes, pass·photons + index,
 * in 64 bits; each 2^32 photons are a stream of their own (the high half picks it), so the
 * sequence never repeats. */
inline Sampler photon_sampler(uint seed, uint pass, int photons, int index) {
  ulong number = (ulong)pass * (ulong)photons + (ulong)index;
  return sampler_start(seed, (uint)(number >> 32), (uint)number, pass, (uint)index);
}

/* Moves to sample `index` of the stream, from its first dimension pair (the independent sampler
 * takes a stream of its own for it, so a pass split over launches draws the same numbers). */
inline void sampler_next_sample(Sampler* s, uint index) {
#if KASHA_SOBOL
  s->index = index;
  s->pair = 0;
#else
  s->rng = rng_seed(s->seed ^ 0x68e31da4u, index, s->item);
#endif
}

/* The next dimension pair. */
inline float2 sample_2d(Sampler* s) {
#if KASHA_SOBOL
  return scrambled_sobol_2d(s->index, hash_combine(s->key, s->pair++));
#else
  return rng_next_float2(&s->rng);
#endif
}

/* Puts the sampler at dimension pair `pair`, so that each path vertex draws from the same
 * dimensions whatever branches came before (no-op for independent numbers). */
inline void sampler_at(Sampler* s, uint pair) {
#if KASHA_SOBOL
  s->pair = pair;
#endif
}

#endif
