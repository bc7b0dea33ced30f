#pragma once
// The analytic fluorescent furnace of docs/design.md#the-fluorescent-furnace: a closed enclosure
// whose inside is one uniform material (passive ρ, fluorescent ê aᵀ, no gloss or an ideal mirror of
// reflectance g) emitting the same Lambertian radiance Le everywhere has uniform radiance
//   L = B⁻¹Le + B⁻¹ê · (aᵀB⁻¹Le) / (1 − aᵀB⁻¹ê),   B = diag(1 − g − ρ).
#include <string>
#include <vector>

#include "film/image.h"
#include "scene/scene.h"

namespace kasha {

struct Furnace {
  bool qualifies = false;
  std::string why_not;           // when it does not
  std::vector<double> radiance;  // L per bin
};

// Checks that the scene is such an enclosure with the camera inside, and solves for L.
Furnace analyze_furnace(const Scene& scene);

// The image every camera inside sees: L in every pixel (XYZ, and per bin when spectral).
Image furnace_image(const Scene& scene, const std::vector<double>& radiance, bool spectral);

}  // namespace kasha
