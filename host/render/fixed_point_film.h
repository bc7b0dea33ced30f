#pragma once
// The light splats' film on the host (forward's, vcm's light tracing's): 128-bit unsigned fixed
// point per film cell, two 64-bit words (lo, hi) that kernels/film/film_splat.h adds to exactly, in
// units of 2^-shift of a film value.
#include <cstdint>
#include <vector>

#include "render/device_scene.h"

namespace kasha {

// The shift that maps the scene's reference film value V (fixed_point_film.cpp) to 2^64, so the
// 64 bits below it resolve any splat and the 63 above hold any pixel's sum over a pass.
int fixed_point_shift(const KernelSceneData& scene, const std::vector<float>& cmf, bool spectral);

// A cell's film value, (hi·2^64 + lo)·2^-shift.
double fixed_point_value(uint64_t lo, uint64_t hi, int shift);

}  // namespace kasha
