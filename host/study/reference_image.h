#pragma once
// Reference images for error-against-time comparisons when no analytic one exists: rendered with
// the lowest-variance unbiased integrator kasha has — backward, with next-event estimation and MIS
// (forward is unbiased too but sees the camera side of a scene through light paths alone; photon
// mapping is biased). The EXR records how it was made.
#include <optional>
#include <string>

#include "film/image.h"
#include "render/device_set.h"
#include "scene/scene.h"

namespace kasha {

// `--reference furnace`: the analytic furnace's image instead of a file.
constexpr const char* kFurnaceReference = "furnace";

// The reference that `--reference` names for a render of `scene`, checked before anything is
// rendered: none (empty), the analytic furnace's image (the scene must be one) or an EXR of the
// scene's size.
std::optional<Image> reference_for(const std::string& reference, const Scene& scene, bool spectral);

struct ReferenceInfo {
  std::string integrator, scene_fingerprint;
  double seconds = 0;
  long long samples_per_pixel = 0;
};

// A fingerprint of the scene file's bytes, to tell whether a cached reference still fits it.
std::string scene_fingerprint(const std::string& scene_path);

Image render_reference(DeviceSet& devices, const Scene& scene, double seconds, unsigned seed,
                       ReferenceInfo& info, bool show_progress);
void write_reference(const std::string& path, const Image& image, const ReferenceInfo& info);
// The provenance of a reference EXR written by write_reference; empty integrator if it has none.
ReferenceInfo read_reference_info(const std::string& path);

}  // namespace kasha
