#include "scene/pbrt/pbrt_subdivision.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace kasha {

namespace {

using Vec = Eigen::Vector3d;
using Tri = std::array<int, 3>;

std::uint64_t edge_key(int a, int b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b));
}

// β of an interior vertex of valence n (pbrt-v4's `beta`).
double beta(int n) {
  return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
}

// A mesh's connectivity: each vertex's neighbours, and which of them lie across a boundary edge.
struct Rings {
  std::vector<std::vector<int>> neighbours, boundary;
};

Rings rings_of(size_t vertices, const std::vector<Tri>& tris,
               const std::unordered_map<std::uint64_t, int>& edge_faces) {
  Rings r;
  r.neighbours.resize(vertices);
  r.boundary.resize(vertices);
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      r.neighbours[a].push_back(b);
      r.neighbours[b].push_back(a);
      if (edge_faces.at(edge_key(a, b)) != 2) {
        r.boundary[a].push_back(b);
        r.boundary[b].push_back(a);
      }
    }
  for (size_t v = 0; v < vertices; ++v) {
    for (auto* list : {&r.neighbours[v], &r.boundary[v]}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
  }
  return r;
}

std::unordered_map<std::uint64_t, int> count_edge_faces(const std::vector<Tri>& tris) {
  std::unordered_map<std::uint64_t, int> faces;
  faces.reserve(tris.size() * 2);
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) ++faces[edge_key(t[k], t[(k + 1) % 3])];
  return faces;
}

// The new position of an old vertex after one level, or its limit position (`limit`).
Vec smoothed(int v, const std::vector<Vec>& p, const Rings& r, bool limit) {
  const std::vector<int>& b = r.boundary[v];
  if (!b.empty()) {
    // A boundary vertex moves along the boundary only; one with other than two boundary
    // neighbours (a corner of a non-manifold fan) stays.
    if (b.size() != 2) return p[v];
    const double w = limit ? 1.0 / 5.0 : 1.0 / 8.0;
    return (1 - 2 * w) * p[v] + w * (p[b[0]] + p[b[1]]);
  }
  const std::vector<int>& ring = r.neighbours[v];
  const int n = static_cast<int>(ring.size());
  if (n == 0) return p[v];
  const double w = limit ? 1.0 / (n + 3.0 / (8.0 * beta(n))) : beta(n);
  Vec sum = Vec::Zero();
  for (int q : ring) sum += p[q];
  return (1 - n * w) * p[v] + w * sum;
}

}  // namespace

SubdividedMesh loop_subdivide(const std::vector<double>& positions,
                              const std::vector<double>& indices, int levels) {
  std::vector<Vec> p(positions.size() / 3);
  for (size_t i = 0; i < p.size(); ++i)
    p[i] = Vec(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
  std::vector<Tri> tris(indices.size() / 3);
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) tris[t][k] = static_cast<int>(indices[3 * t + k]);

  for (int level = 0; level < levels; ++level) {
    const auto edge_faces = count_edge_faces(tris);
    const Rings r = rings_of(p.size(), tris, edge_faces);
    // Even vertices: the old ones, smoothed.
    std::vector<Vec> next(p.size());
    for (size_t v = 0; v < p.size(); ++v) next[v] = smoothed(static_cast<int>(v), p, r, false);
    // Odd vertices: one per edge, 3/8 of its ends and 1/8 of the two opposite corners (the
    // midpoint on a boundary).
    std::unordered_map<std::uint64_t, int> odd;
    std::unordered_map<std::uint64_t, Vec> opposite_sum;
    odd.reserve(edge_faces.size());
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k)  // Eigen leaves a default vector uninitialised: start at zero
        opposite_sum.try_emplace(edge_key(t[k], t[(k + 1) % 3]), Vec::Zero()).first->second +=
            p[t[(k + 2) % 3]];
    std::vector<Tri> split;
    split.reserve(tris.size() * 4);
    const auto odd_vertex = [&](int a, int b) {
      const std::uint64_t key = edge_key(a, b);
      auto found = odd.find(key);
      if (found != odd.end()) return found->second;
      const Vec x = edge_faces.at(key) == 2
                        ? Vec(3.0 / 8.0 * (p[a] + p[b]) + 1.0 / 8.0 * opposite_sum.at(key))
                        : Vec(0.5 * (p[a] + p[b]));
      next.push_back(x);
      const int index = static_cast<int>(next.size()) - 1;
      odd.emplace(key, index);
      return index;
    };
    for (const Tri& t : tris) {
      const int m01 = odd_vertex(t[0], t[1]), m12 = odd_vertex(t[1], t[2]),
                m20 = odd_vertex(t[2], t[0]);
      split.push_back({t[0], m01, m20});
      split.push_back({t[1], m12, m01});
      split.push_back({t[2], m20, m12});
      split.push_back({m01, m12, m20});
    }
    p = std::move(next);
    tris = std::move(split);
  }

  // The limit positions, then normals from the faces around each vertex.
  const Rings r = rings_of(p.size(), tris, count_edge_faces(tris));
  std::vector<Vec> limit(p.size());
  for (size_t v = 0; v < p.size(); ++v) limit[v] = smoothed(static_cast<int>(v), p, r, true);
  std::vector<Vec> normal(p.size(), Vec::Zero());
  for (const Tri& t : tris) {
    const Vec n = (limit[t[1]] - limit[t[0]]).cross(limit[t[2]] - limit[t[0]]);
    for (int k = 0; k < 3; ++k) normal[t[k]] += n;
  }
  SubdividedMesh out;
  out.positions.reserve(3 * limit.size());
  out.normals.reserve(3 * limit.size());
  for (size_t v = 0; v < limit.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      out.positions.push_back(limit[v][c]);
      out.normals.push_back(normal[v][c]);  // a zero one shades its triangles flat
    }
  out.indices.reserve(3 * tris.size());
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) out.indices.push_back(t[k]);
  return out;
}

}  // namespace kasha
