#pragma once
// pbrt-v4's `Shape` directive as a kasha shape in the shape's object space
// (docs/pbrt-import.md#shapes): triangle, bilinear and Loop-subdivided meshes as "triangles", PLY
// files as "mesh",
// spheres, disks and cylinders tessellated with pbrt-v4's (u, v) and exact shading normals.
#include <nlohmann/json.hpp>
#include <string>

#include "scene/pbrt/pbrt_materials.h"
#include "scene/pbrt/pbrt_parameters.h"

namespace kasha {

// Segments around a tessellated sphere, cylinder or disk (and half as many rings along a
// sphere): 256 keeps a unit sphere within 8·10⁻⁵ of its surface, and its normals are exact.
constexpr int kPbrtSegments = 256;
// A `loopsubdiv` may make at most this many triangles (four per triangle a level).
constexpr long kMaxSubdividedTriangles = 1L << 25;

// The kasha shape (without "material", "transform" or emission), or null for a shape kasha leaves
// out with a warning (curves).
nlohmann::json pbrt_shape(const std::string& type, const PbrtParameters& params,
                          const PbrtLocation& where);

// The shape's "alpha" (a number, or a float texture's name) as kasha's shape "alpha"
// (docs/formats.md#alpha); nothing for alpha 1.
void pbrt_shape_alpha(const PbrtParameters& params, const PbrtTextures& textures,
                      nlohmann::json& shape);

}  // namespace kasha
