#pragma once
// The radius policy that photon mapping and vertex merging share: the first radius comes from a
// pixel's footprint, and no radius goes beyond a fiftieth of the scene's diagonal — one pixel of
// a tiny image would otherwise gather over whole walls, biasing the estimate far beyond its first
// passes. A --radius beyond that is said once, in the same words for every integrator.
#include "scene/scene.h"
#include "shared/shared_types.h"

namespace kasha {

struct MergeRadiusBounds {
  double footprint = 0;        // a pixel's width on the image plane at unit distance
  double largest = 0;          // 1/50 of the scene's diagonal
  double centre_distance = 0;  // from the camera to the centre of the scene's bounds
};

MergeRadiusBounds merge_radius_bounds(const Scene& scene, const KCamera& camera);

// Warns that --radius `radius` lies beyond bounds.largest, which is used instead.
void warn_radius_beyond(double radius, const MergeRadiusBounds& bounds);

}  // namespace kasha
