#pragma once
// A triangle's ∂p/∂u as pbrt-v4's Triangle::InteractionFromIntersection derives it from its
// texture coordinates: the x axis of an anisotropic roughness (docs/materials.md#rough-surfaces).
#include "scene/shape_mesh.h"

namespace kasha {

// For texture coordinates that span no area (or a dpdu × dpdv of zero), pbrt-v4's fallback: the
// first axis of its CoordinateSystem about the normalised (p2 − p0) × (p1 − p0).
Eigen::Vector3d triangle_dpdu(const Triangle& p, const TriangleUv& uv);

}  // namespace kasha
