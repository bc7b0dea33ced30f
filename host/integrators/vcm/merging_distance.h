#pragma once
// Where a camera path's merging vertex (its first that is not delta) typically lies, from a
// 32 × 32 grid of camera rays (Embree on the host) followed through mirrors and metals by
// reflection and through glass straight on (its bending left out: a scale is all that is wanted):
// how far the path travels to it, which sets vcm's and ppm's hashed grid's cell and caps their
// radii (a pixel's footprint there), and how many of those vertices no lamp lights directly.
// Only speed depends on either: both subpaths weigh a merge by the same radius, and every path's
// weights sum to one whatever the number of light subpaths.
#include "geometry/embree_scene.h"
#include "scene/scene.h"
#include "shared/shared_types.h"

namespace kasha {

struct MergingVertices {
  double distance = 0;  // the median distance; 0 when no ray meets such a surface
  // The share of them that see the front of no emitting triangle (of up to 64 points spread over
  // the emitters, the triangles' centroids): lit only through other surfaces, by light that next-
  // event estimation does not bring and light subpaths must (connections, merges). 0 where the
  // scene has lights that are not shapes (a sun, a sky light by next-event estimation, unprobed).
  double unlit = 0;
};

MergingVertices probe_merging_vertices(const Scene& scene, const EmbreeScene& embree,
                                       const KCamera& camera);

}  // namespace kasha
