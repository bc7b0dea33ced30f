#pragma once
// Bytes of photon mapping's records for a scene and film, for its stores and `kasha info`
// (kernels/shared/photon_layout.h): a stored photon holds (8 + N) floats, a visible point 8 + N, or
// 8 + 2N + R in a fluorescent scene; with scattering media a photon 3 more (its direction) and a
// visible point 4 (ωo and g).
#include <cstddef>

#include "scene/scene.h"
#include "shared/photon_layout.h"

namespace kasha {

inline size_t photon_record_bytes(const Scene& scene) {
  return KASHA_PHOTON_FLOATS(scene.grid.bins, scene.scattering()) * sizeof(float);
}

inline size_t visible_point_bytes(const Scene& scene, bool spectral_film) {
  const int rows = spectral_film ? scene.grid.bins : 3;
  return KASHA_VP_FLOATS(scene.grid.bins, rows, scene.fluorescent(), scene.scattering()) * sizeof(float);
}

}  // namespace kasha
