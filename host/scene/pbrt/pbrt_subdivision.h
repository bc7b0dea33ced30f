#pragma once
// Loop subdivision (Loop 1987), as pbrt-v4's `loopsubdiv` shape: each level splits every triangle
// in four and smooths the vertices (Warren's weights: β = 3/16 at valence 3, 3/(8n) above), then
// the vertices move to their limit positions. Boundaries follow the cubic B-spline rules.
#include <array>
#include <vector>

namespace kasha {

struct SubdividedMesh {
  std::vector<double> positions;  // x y z per vertex
  std::vector<double> normals;    // per vertex: the area-weighted mean of its faces' normals
  std::vector<double> indices;    // three per triangle, the input's winding
};

// `positions` x y z per vertex, `indices` three per triangle (each naming a vertex), `levels`
// in [0, 10]. Edges shared by more than two triangles are treated as boundaries.
SubdividedMesh loop_subdivide(const std::vector<double>& positions,
                              const std::vector<double>& indices, int levels);

}  // namespace kasha
