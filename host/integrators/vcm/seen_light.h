#pragma once
// The pixels where the camera sees light through delta bounces alone — a lamp, the sky, their
// images in glass, a mirror or a smooth coat — which vcm takes there from extra samples of the
// pixel (kernels/vcm/vcm_seen_light.h; so do bpt and ppm): a lamp's edges converge with a
// pixel's samples. Chosen
// before the render from the geometry alone, so which pixels take them biases nothing; elsewhere
// the extra samples would find nothing and only cost rays.
#include <vector>

#include "geometry/embree_scene.h"
#include "scene/scene.h"
#include "shared/shared_types.h"

namespace kasha {

// Per pixel, 1 where the light seen has an edge: of 2 × 2 camera rays through it and through
// each pixel beside it, some reach the front of an emitting triangle, or leave the scene where an
// infinite light is, through delta bounces alone — smooth glass (reflection and refraction both
// followed), smooth metal, ideal mirror lobes and smooth coats, up to 8 of them and 32 rays a
// probe — and some do
// not. Inside a lamp (or a furnace's emitter, or a mirror that shows only it) every sample sees
// the same light, and extra ones would only cost rays. Embree on the host.
std::vector<int> seen_light_pixels(const Scene& scene, const EmbreeScene& embree,
                                   const KCamera& camera);

}  // namespace kasha
