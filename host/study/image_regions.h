#pragma once
// Where each shape is in an image, found with Embree from the scene's camera (independently of the
// integrators), and an image's mean XYZ over such a region — how a rendered sample is measured, as
// a photographed one would be.
#include <vector>

#include "color/color_space.h"
#include "film/image.h"
#include "scene/scene.h"

namespace kasha {

struct ShapeRegion {
  int shape = -1;              // index into Scene::shapes
  std::vector<size_t> pixels;  // row-major, row 0 at the top
};

// Pixels grouped by the shape seen first through their centres; shapes the camera does not see
// are left out. With margin_px > 0 a pixel counts only if the rays through the eight points
// margin_px away from its centre (its 3 × 3 neighbourhood at that spacing) see the same shape:
// pixels well inside the shape, clear of its edges and of anything in front of it.
std::vector<ShapeRegion> shape_regions(const Scene& scene, const Camera& camera,
                                       double margin_px = 0);

struct RegionXyz {
  Vec3d mean{0, 0, 0}, standard_error{0, 0, 0};  // over the pixels, independent estimates
};
RegionXyz region_xyz(const Image& image, const std::vector<size_t>& pixels);

}  // namespace kasha
