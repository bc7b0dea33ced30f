#pragma once
// What the camera sees first through a point of its image, found with Embree (independently of
// the integrators): the ground the image-region measurements (sample regions, lamp pixels) use.
#include "geometry/embree_scene.h"
#include "scene/scene.h"

namespace kasha {

class PrimaryRays {
 public:
  PrimaryRays(const Scene& scene, const Camera& camera);
  // The triangle (scene order) seen through image point (px, py), in pixels from the top-left
  // corner, or -1; `front` (if given) says whether the ray meets its front side. The ray is built
  // in float, as the kernels' camera builds it.
  int triangle(double px, double py, bool* front = nullptr) const;

 private:
  const Scene& scene_;
  EmbreeScene embree_;
  KCamera camera_;
  int width_, height_;
};

}  // namespace kasha
