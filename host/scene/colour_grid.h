#pragma once
// A medium whose colour varies over its grid (docs/media.md#colour-grids; pbrt-v4's "rgbgrid"):
// σa and σs given per sample as linear sRGB colours of any size, each pbrt-v4's
// RGBUnboundedSpectrum, trilinear between the samples (an absent one is 1 everywhere in the box).
// The kernels track such a medium exactly as a sum of components (kernels/media/colour_grid.h),
// σt(λ, x) = Σ_k ρ_k(x) σt_k(λ): the samples whose colours are equal up to a factor share one
// component (pbrt-v4's spectrum of c·rgb is c times that of rgb), and where more colours differ
// than the wavelength grid has bins each bin is one instead. Either way the weights are not
// negative and the sum is exact.
#include <vector>

#include "scene/medium.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

// The components of grid g's colours (g.sigma_a_rgb, g.sigma_s_rgb) times `scale`, on the
// wavelength grid; a box-wide one (an absent colour list) comes last, and none whose weights are
// all 0 is kept.
std::vector<GridComponent> colour_grid_components(const DensityGrid& g, double scale,
                                                  const WavelengthGrid& grid);

// The components of an emitting colour grid's radiance (g.emission_rgb, each pbrt-v4's
// RGBIlluminantSpectrum) times `scale`, split alike; none whose weights are all 0 is kept.
std::vector<EmissionComponent> colour_grid_emission(const DensityGrid& g, double scale,
                                                    const WavelengthGrid& grid);

}  // namespace kasha
