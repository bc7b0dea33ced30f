/* Next-event estimation's choice of emitting triangle given the shading point x: pbrt-v4's
 * BVHLightSampler over the emitting triangles (KLightNode, built by host/render/light_bvh.cpp).
 * Sampling descends from the root, choosing each node's child in proportion to its importance
 * at x; the probability of a triangle walks the same path by its trail, multiplying the same
 * ratios, so the two agree exactly (multiple importance sampling depends on it). No stack: one
 * root-to-leaf path either way. */
#ifndef KASHA_LIGHT_BVH_H
#define KASHA_LIGHT_BVH_H

#include "shared/shared_types.h"

/* pbrt-v4's LightBounds::Importance without a receiver normal (its n = 0: the callers of
 * light_pdf_from have none): the power over the squared distance to the box's centre (at least
 * half the box's diagonal, as pbrt-v4 clamps), times the cosine of the smallest angle between a
 * normal in the cone and the direction to x from a point in the box; 0 when that angle exceeds
 * θe = π/2, so a cluster facing away from x gets nothing. */
inline float light_importance(const __global KLightNode* n, float3 x) {
  float3 lo = (float3)(n->lo[0], n->lo[1], n->lo[2]), hi = (float3)(n->hi[0], n->hi[1], n->hi[2]);
  float3 w = (float3)(n->w[0], n->w[1], n->w[2]);
  float3 diag = hi - lo, d = x - 0.5f * (lo + hi);
  float dc2 = dot(d, d), r2 = 0.25f * dot(diag, diag);
  float d2 = fmax(dc2, 0.5f * sqrt(dot(diag, diag)));
  /* θw: from the cone's axis to x (any, where x is the centre: the box then holds x). */
  float cos_w = dc2 > 0.0f ? dot(w, d) * rsqrt(dc2) : 1.0f;
  float sin_w = sqrt(fmax(0.0f, 1.0f - cos_w * cos_w));
  /* θb: the half-angle of the box's bounding sphere seen from x, π when x is inside it. */
  float cos_b = dc2 < r2 ? -1.0f : sqrt(fmax(0.0f, 1.0f - r2 / dc2));
  float sin_b = sqrt(fmax(0.0f, 1.0f - cos_b * cos_b));
  float cos_o = n->cos_o, sin_o = sqrt(fmax(0.0f, 1.0f - cos_o * cos_o));
  /* θ' = max(0, θw − θo − θb), by pbrt-v4's clamped differences of sines and cosines. */
  float cos_x = cos_w > cos_o ? 1.0f : cos_w * cos_o + sin_w * sin_o;
  float sin_x = cos_w > cos_o ? 0.0f : sin_w * cos_o - cos_w * sin_o;
  float cos_p = cos_x > cos_b ? 1.0f : cos_x * cos_b + sin_x * sin_b;
  return cos_p > 0.0f ? n->phi * cos_p / d2 : 0.0f;
}

/* The weights of interior node `node`'s two children at x: their importance, or where both have
 * none (a node's bounds are looser than its children's: pbrt-v4 gives up there), their power, so
 * every node passes all its probability on and the triangles' probabilities sum to 1. */
inline void light_bvh_children(const __global KLightNode* nodes, int node, float3 x, float* c0, float* c1) {
  const __global KLightNode* first = &nodes[node + 1];
  const __global KLightNode* second = &nodes[nodes[node].child];
  *c0 = light_importance(first, x);
  *c1 = light_importance(second, x);
  if (!(*c0 + *c1 > 0.0f)) {
    *c0 = first->phi;
    *c1 = second->phi;
  }
}

/* The emitting triangle (leaf order) the descent from the root reaches at x with *u, and in *pmf
 * its probability; *u is rescaled at each node to the part of [0, 1) that chose the child, so it
 * can go on to pick the point. */
inline int light_bvh_sample(const __global KLightNode* nodes, float3 x, float* u, float* pmf) {
  int node = 0;
  *pmf = 1.0f;
  while (nodes[node].child >= 0) {
    int second = nodes[node].child;
    float c0, c1;
    light_bvh_children(nodes, node, x, &c0, &c1);
    float sum = c0 + c1, p0 = c0 / sum;
    if (*u < p0) {
      *u = fmin(*u / p0, 0.99999994f);
      *pmf *= p0;
      ++node;
    } else {
      /* c1 / sum, not 1 − p0: the same expression light_bvh_pmf multiplies. */
      *u = fmin((*u - p0) / (1.0f - p0), 0.99999994f);
      *pmf *= c1 / sum;
      node = second;
    }
  }
  return ~nodes[node].child;
}

/* The probability that light_bvh_sample at x reaches the leaf at the end of `trail`. */
inline float light_bvh_pmf(const __global KLightNode* nodes, ulong trail, float3 x) {
  int node = 0;
  float pmf = 1.0f;
  while (nodes[node].child >= 0) {
    int second = nodes[node].child;
    float c0, c1;
    light_bvh_children(nodes, node, x, &c0, &c1);
    float sum = c0 + c1;
    if (trail & 1) {
      pmf *= c1 / sum;
      node = second;
    } else {
      pmf *= c0 / sum;
      ++node;
    }
    trail >>= 1;
  }
  return pmf;
}

#endif
