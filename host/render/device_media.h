#pragma once
// The scene's participating media in kernel layout (kernels/media/medium.h, docs/media.md): each
// medium's extinction and scattering spectra, and each leaf triangle's medium interface.
#include <vector>

#include "scene/scene.h"
#include "shared/shared_types.h"

namespace kasha {

struct DeviceMedia {
  std::vector<KMedium> media;
  std::vector<KTriMedia> tri_media;  // per leaf triangle; empty when no shape bounds a medium
  int trail_slots =
      0;  // a MediaTrail's slots: one per medium, and a colour grid's further components
};

// `leaf_triangles`: the BVH's triangles in leaf order (their prim is the scene order);
// `light_power`: the lights' and emitters' (W), against which emitting media take their share of
// light paths; spectra are appended to `spectra` at the KMedium offsets.
DeviceMedia device_media(const Scene& scene, const std::vector<KTriangle>& leaf_triangles,
                         double light_power, std::vector<float>& spectra);

}  // namespace kasha
