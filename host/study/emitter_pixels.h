#pragma once
// The pixels in which an emitter is seen directly: any of a 4 × 4 grid of rays through the pixel
// hits an emitter's front first (found with Embree, independently of the integrators). Error
// figures "with the lamp's pixels left out" measure what a renderer does with the light it
// gathers, apart from antialiasing a lamp's edges.
#include <vector>

#include "scene/scene.h"

namespace kasha {

std::vector<bool> emitter_pixels(const Scene& scene);

}  // namespace kasha
