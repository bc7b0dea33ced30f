#include "scene/colour_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>

#include "spectrum/rgb_spectrum.h"

namespace kasha {

namespace {

// pbrt-v4's RGBUnboundedSpectrum of a colour whose largest part is 1, on the grid: 2·S(rgb/2).
std::vector<double> unit_colour_spectrum(const std::array<float, 3>& key,
                                         const WavelengthGrid& grid) {
  RgbReflectanceSpectrum s({key[0] / 2.0, key[1] / 2.0, key[2] / 2.0});
  std::vector<double> out = grid.resample(s);
  for (double& v : out) v *= 2;
  return out;
}

// Colours (3 per sample) split as non-negative components, each weights per sample and a
// spectrum: a class of colours equal up to a factor each (its weights the factors, its spectrum
// `unit`'s of the class's colour scaled to a largest part of 1 — pbrt-v4's spectrum of c·rgb is c
// times that of rgb), or one per bin where more classes than bins differ.
struct ColourPart {
  std::vector<float> values;
  std::vector<double> spectrum;
};

std::vector<ColourPart> colour_parts(
    const std::vector<float>& rgb, const WavelengthGrid& grid,
    const std::function<std::vector<double>(const std::array<float, 3>&)>& unit) {
  const size_t samples = rgb.size() / 3;
  // Colours equal up to a factor to one part in 2^20 (c·rgb rounds apart from rgb in the last
  // bits): a class's spectrum, its first colour's, is then each member's to about 10⁻⁶.
  std::map<std::array<long, 3>, int> classes;
  std::vector<std::array<float, 3>> keys;
  std::vector<int> of(samples, -1);
  std::vector<float> factor(samples, 0.0f);
  for (size_t v = 0; v < samples; ++v) {
    const float r = rgb[3 * v], g = rgb[3 * v + 1], b = rgb[3 * v + 2], m = std::max({r, g, b});
    if (!(m > 0)) continue;
    const std::array<float, 3> key = {r / m, g / m, b / m};
    const std::array<long, 3> rounded = {std::lround(key[0] * 0x1p20), std::lround(key[1] * 0x1p20),
                                         std::lround(key[2] * 0x1p20)};
    const auto [at, added] = classes.emplace(rounded, static_cast<int>(classes.size()));
    if (added) keys.push_back(key);
    of[v] = at->second;
    factor[v] = m;
  }
  std::vector<std::vector<double>> spectra(classes.size());
  for (size_t c = 0; c < keys.size(); ++c) spectra[c] = unit(keys[c]);
  std::vector<ColourPart> out;
  if (classes.size() <= static_cast<size_t>(grid.bins)) {
    for (size_t c = 0; c < classes.size(); ++c) {
      ColourPart k{std::vector<float>(samples, 0.0f), spectra[c]};
      for (size_t v = 0; v < samples; ++v)
        if (of[v] == static_cast<int>(c)) k.values[v] = factor[v];
      out.push_back(std::move(k));
    }
    return out;
  }
  for (int i = 0; i < grid.bins; ++i) {
    ColourPart k{std::vector<float>(samples, 0.0f), std::vector<double>(grid.bins, 0.0)};
    k.spectrum[i] = 1;
    for (size_t v = 0; v < samples; ++v)
      if (of[v] >= 0) k.values[v] = static_cast<float>(factor[v] * spectra[of[v]][i]);
    out.push_back(std::move(k));
  }
  return out;
}

// One coefficient's colours as components (σs's also extinguish).
void coefficient_components(const std::vector<float>& rgb, bool scatters, double scale,
                            const WavelengthGrid& grid, std::vector<GridComponent>& out) {
  const auto unit = [&](const std::array<float, 3>& key) {
    return unit_colour_spectrum(key, grid);
  };
  for (ColourPart& part : colour_parts(rgb, grid, unit)) {
    GridComponent k;
    for (double& x : part.spectrum) x *= scale;
    k.sigma_t = part.spectrum;
    k.sigma_s = scatters ? part.spectrum : std::vector<double>(part.spectrum.size(), 0.0);
    k.values = std::move(part.values);
    out.push_back(std::move(k));
  }
}

}  // namespace

std::vector<GridComponent> colour_grid_components(const DensityGrid& g, double scale,
                                                  const WavelengthGrid& grid) {
  std::vector<GridComponent> out;
  GridComponent uniform;
  uniform.sigma_t.assign(grid.bins, 0.0);
  uniform.sigma_s.assign(grid.bins, 0.0);
  for (const bool scatters : {false, true}) {
    const std::vector<float>& rgb = scatters ? g.sigma_s_rgb : g.sigma_a_rgb;
    if (!rgb.empty()) {
      coefficient_components(rgb, scatters, scale, grid, out);
      continue;
    }
    // pbrt-v4: an absent grid is 1 (times the scale) everywhere in the box.
    for (double& v : uniform.sigma_t) v += scale;
    if (scatters)
      for (double& v : uniform.sigma_s) v += scale;
  }
  out.erase(std::remove_if(out.begin(), out.end(),
                           [](const GridComponent& k) {
                             return std::none_of(k.values.begin(), k.values.end(),
                                                 [](float v) { return v > 0; });
                           }),
            out.end());
  if (std::any_of(uniform.sigma_t.begin(), uniform.sigma_t.end(), [](double v) { return v > 0; }))
    out.push_back(std::move(uniform));
  return out;
}

std::vector<EmissionComponent> colour_grid_emission(const DensityGrid& g, double scale,
                                                    const WavelengthGrid& grid) {
  // pbrt-v4's RGBIlluminantSpectrum, also linear in the colour's size.
  const auto unit = [&](const std::array<float, 3>& key) {
    return grid.resample(RgbIlluminantSpectrum({key[0], key[1], key[2]}));
  };
  std::vector<EmissionComponent> out;
  for (ColourPart& part : colour_parts(g.emission_rgb, grid, unit)) {
    if (std::none_of(part.values.begin(), part.values.end(), [](float v) { return v > 0; }))
      continue;
    for (double& x : part.spectrum) x *= scale;
    out.push_back({std::move(part.values), std::move(part.spectrum)});
  }
  return out;
}

}  // namespace kasha
