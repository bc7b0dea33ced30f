#pragma once
// A rough layered metal (docs/materials.md#rough-coated-conductors): pbrt-v4's coatedconductor
// with a rough interface or a rough conductor, as a sum of three parts the kernels already have
// or have beside the bare conductor:
//   - the coat's reflection (a mirror of F(θ), or a rough coat's GGX lobe);
//   - the metal seen through the coat, scattered once (kernels/materials/metal_under_coat.h);
//   - everything else that leaves the layer: light the metal sends beyond the coat's escape
//     cone or that the coat reflects back, after its later round trips — a coated Lambert part
//     whose albedo per wavelength is that light's, found by a random walk here.
// The scene keeps the material as a mix whose points choose the metal part or the coated
// Lambert part (which carries the coat's reflection), each scaled by 1 / its share, so the
// image's expectation is the sum.
#include <vector>

#include "material/coat.h"

namespace kasha {

// The metal's GGX alpha seen through a rough coat by smooth refraction: each crossing of a
// coat of roughness αc turns a direction by about αc (1 − 1/η) inside, so
// α² = α_metal² + αc² (1 − 1/η)² / 2 (two crossings; a reflection doubles a facet's tilt);
// at least 1e-3 (a rough lobe).
double layered_metal_alpha(const CoatDesc& coat, double alpha_metal);

struct LayeredMetalParts {
  std::vector<double> scattered;  // per bin: the Lambert part's ρ (no internal reflectance)
  double lambert_share = 0;       // of points, the share that takes the coated Lambert part
  double once_scale = 1;          // the once-scattered lobe's factor (1 under a smooth coat)
  std::vector<double> shape;      // the Lambert part's t(μ) = η s(μ) at kCoatTableSize cosines
};

// The parts for a metal of index eta + ik per bin (over the outside's) and GGX alpha alpha_metal
// under `coat`; `alpha` is its lobe's seen through the coat (layered_metal_alpha's). A random
// walk through the layer as pbrt-v4 takes it (rough interfaces scattering once at each crossing,
// every bounce kept; fixed seed) gives, for light arriving cosine-weighted, the albedo of what
// leaves the layer per bin; the coated Lambert part's ρ makes up what the once-scattered lobe
// does not give of it, under uniform light.
LayeredMetalParts layered_metal_parts(const CoatDesc& coat, double alpha_metal, double alpha,
                                      const std::vector<double>& eta, const std::vector<double>& k);

}  // namespace kasha
