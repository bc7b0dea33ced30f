#pragma once
// Which emitting shapes are sphere lights: triangles tessellating a sphere (every vertex on it),
// fronts outward, that next-event estimation samples as one light by the solid angle the sphere
// subtends (docs/integrators.md#light-sampling, kernels/lights/sphere_light.h).
#include <Eigen/Geometry>
#include <optional>

#include "scene/shape_mesh.h"

namespace kasha {

struct SphereBound {
  Eigen::Vector3d centre;
  double radius = 0;
};

// The sphere `mesh` (world space) tessellates, given the sphere it was made from in its own space
// and the transform that placed it: the transformed centre and the vertices' distance from it, if
// every vertex lies at that distance (to 1e-6: the transform is a similarity) and every triangle
// with an area faces away from the centre; none otherwise (the shape stays a plain mesh).
std::optional<SphereBound> tessellated_sphere(const ShapeMesh& mesh, const SphereBound& own,
                                              const Eigen::Affine3d& placed);

}  // namespace kasha
