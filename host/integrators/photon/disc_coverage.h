#pragma once
// How much of a visible point's gather disc lies on surface the gather accepts. Near an edge the
// disc hangs over it: the photons there are rejected by the normal test, but the density estimate
// divides by the whole disc, so the estimate darkens towards edges (the classic photon-mapping
// bias at corners). Probing the disc with short rays along the normal measures the covered
// fraction f, and the pass's flux is divided by it.
#include <vector>

#include "geometry/embree_scene.h"

namespace kasha {

// Per pixel: the covered fraction of the disc of radius[pixel] around its visible point (1 for
// pixels without one), from 16 probes on a stratified pattern rotated by `rotation` (radians).
std::vector<float> disc_coverage(const EmbreeScene& scene, const float* visible_points,
                                 int vp_floats, size_t pixels, const std::vector<double>& radius,
                                 float rotation);

}  // namespace kasha
