#pragma once
// Where light paths start in an emitting medium (docs/media.md#emitting-media; the kernels'
// transport/medium_light.h): a box that holds the medium's region, its volume, whether the medium
// is the one outside every boundary, and roughly what it emits — for the integrators whose light
// paths carry all the light (forward, photon, ppm).
#include <Eigen/Geometry>
#include <optional>

#include "scene/scene.h"

namespace kasha {

struct MediumLightRegion {
  Eigen::Affine3d from_unit = Eigen::Affine3d::Identity();  // the unit cube onto the box
  double volume = 0;          // the box's
  bool outer = false;         // the medium a point past every boundary is in
  double power = 0;           // W, roughly: 4π · volume · mean emission (it sets the picks only)
};

// The medium that points past every medium boundary are in: the side that a ray from past them
// all meets first; without boundaries, the camera's.
int outer_medium(const Scene& scene);

// Medium m's region as light paths sample it: a grid's box, or the box of the boundaries that
// have it on a side (power 0 where it emits nothing); none for a homogeneous medium that emits and
// fills the space past every boundary, or that no boundary holds: no box holds its region.
std::optional<MediumLightRegion> medium_light_region(const Scene& scene, int m);

}  // namespace kasha
