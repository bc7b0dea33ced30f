#pragma once
// How far a camera path typically travels to the vertex where vcm and ppm merge (the first that
// is not delta): it sets their hashed grid's cell and caps their radii, which grow with that
// distance (a pixel's footprint there). Only speed depends on it: both subpaths weigh a merge by
// the same radius whatever it is.
#include "scene/scene.h"
#include "shared_types.h"

namespace kasha {

// The median over a 32 × 32 grid of camera rays (Embree on the host) of the distance to the first
// surface that is not a smooth mirror, metal or glass — followed through mirrors and metals by
// reflection and through glass straight on (its bending left out: a footprint's scale is all that
// is wanted). 0 when no ray meets such a surface.
double merging_distance(const Scene& scene, const KCamera& camera);

}  // namespace kasha
