#include "render/device_media.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "scene/medium_light_region.h"

namespace kasha {

static int append_spectrum(std::vector<float>& spectra, const std::vector<double>& v) {
  const int at = static_cast<int>(spectra.size());
  for (double x : v) spectra.push_back(static_cast<float>(x));
  return at;
}

// A grid's samples onto the spectra buffer: where they start (-1 for none).
static int append_samples(std::vector<float>& spectra, const std::vector<float>& v) {
  if (v.empty()) return -1;
  // The kernels index the spectra buffer with an int.
  if (spectra.size() + v.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw Error("media: the grids' samples exceed 2^31 floats, more than the kernels can index");
  const int at = static_cast<int>(spectra.size());
  spectra.insert(spectra.end(), v.begin(), v.end());
  return at;
}

// A grid's samples into the spectra buffer, and the map from the world to its lattice: the
// medium's space, then the box's unit cube, then n·u − ½ (pbrt-v4's SampledGrid::Lookup).
static void place_grid(const DensityGrid& g, std::vector<float>& spectra, KMedium& k) {
  k.density = append_samples(spectra, g.values);
  k.grid_size[0] = g.nx, k.grid_size[1] = g.ny, k.grid_size[2] = g.nz;
  const Eigen::Vector3d n(g.nx, g.ny, g.nz), extent = g.p1 - g.p0;
  Eigen::Affine3d lattice = Eigen::Affine3d::Identity();
  lattice.translate(Eigen::Vector3d::Constant(-0.5));
  lattice.scale(n.cwiseQuotient(extent));
  lattice.translate(-g.p0);
  const Eigen::Matrix<double, 3, 4> m = (lattice * g.to_world.inverse()).matrix().topRows<3>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) k.to_grid[4 * r + c] = static_cast<float>(m(r, c));
  for (float v : k.to_grid)
    if (!std::isfinite(v))
      throw Error("media: a grid's box or transform maps the world beyond float range");
}

// An emitting grid's scale and temperature samples, and the nodes its blackbody is evaluated at:
// two per bin (Gauss–Legendre), so each bin holds the blackbody's mean over it.
static void place_emission_grids(const Medium& m, const WavelengthGrid& grid,
                                 std::vector<float>& spectra, KMedium& k) {
  k.emission_scale = k.temperature = k.bin_nodes = -1;
  k.temperature_offset = 0.0f, k.temperature_scale = 1.0f;
  if (m.emission.empty() || !m.grid) return;
  k.emission_scale = append_samples(spectra, m.grid->emission_scale);
  if (!m.blackbody) return;
  k.temperature = append_samples(spectra, m.grid->temperature);
  k.temperature_offset = static_cast<float>(m.blackbody->offset);
  k.temperature_scale = static_cast<float>(m.blackbody->scale);
  std::vector<double> nodes;
  for (int i = 0; i < grid.bins; ++i)
    for (double side : {-1.0, 1.0})
      nodes.push_back(grid.center(i) + side * grid.bin_nm / (2 * std::sqrt(3.0)));
  k.bin_nodes = append_spectrum(spectra, nodes);
}

// A colour grid's components (kernels/media/colour_grid.h): their σt and σs spectra end to end
// (in place of the medium's), and trail slots beyond the media's own for
// all but the first.
static void place_components(const Medium& m, std::vector<float>& spectra, KMedium& k,
                             int& trail_slots) {
  k.components = static_cast<int>(m.components.size());
  k.uniform_last = m.components.back().values.empty() ? 1 : 0;
  k.trail_extra = trail_slots;
  trail_slots += k.components - 1;
  k.sigma_t = static_cast<int>(spectra.size());
  for (const GridComponent& c : m.components) append_spectrum(spectra, c.sigma_t);
  k.sigma_s = static_cast<int>(spectra.size());
  for (const GridComponent& c : m.components) append_spectrum(spectra, c.sigma_s);
}

// An emitting colour grid's radiance components (kernels/media/medium_emission.h): their spectra
// end to end at `emission`, their weights end to end at `emission_scale`.
static void place_emission_components(const Medium& m, std::vector<float>& spectra, KMedium& k) {
  k.emission_components = static_cast<int>(m.emission_components.size());
  k.emission = static_cast<int>(spectra.size());
  for (const EmissionComponent& c : m.emission_components) append_spectrum(spectra, c.radiance);
  k.emission_scale = static_cast<int>(spectra.size());
  for (const EmissionComponent& c : m.emission_components) append_samples(spectra, c.values);
}

// Its components' weights end to end (the box-wide one, last, has none): where they start.
static int place_component_grids(const Medium& m, std::vector<float>& spectra) {
  const int at = static_cast<int>(spectra.size());
  for (const GridComponent& c : m.components) append_samples(spectra, c.values);
  return at;
}

// Each emitting medium's share of the light paths that start in media (forward, photon and ppm:
// kernels/transport/medium_light.h), against the lights' `light_power`, and its box.
static void place_medium_lights(const Scene& scene, double light_power,
                                std::vector<KMedium>& media) {
  const std::vector<bool> used = scene.used_media();
  std::vector<std::optional<MediumLightRegion>> regions(media.size());
  double total = light_power;
  for (size_t m = 0; m < media.size(); ++m) {
    if (!used[m]) continue;
    regions[m] = medium_light_region(scene, static_cast<int>(m));
    if (regions[m]) total += regions[m]->power;
  }
  for (size_t m = 0; m < media.size(); ++m) {
    KMedium& k = media[m];
    if (!regions[m] || !(regions[m]->power > 0) || !(total > 0)) continue;
    k.light_pick = static_cast<float>(regions[m]->power / total);
    k.light_volume = static_cast<float>(regions[m]->volume);
    k.light_outer = regions[m]->outer ? 1 : 0;
    const Eigen::Matrix<double, 3, 4> a = regions[m]->from_unit.matrix().topRows<3>();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) k.light_box[4 * r + c] = static_cast<float>(a(r, c));
  }
}

DeviceMedia device_media(const Scene& scene, const std::vector<KTriangle>& leaf_triangles,
                         double light_power, std::vector<float>& spectra) {
  DeviceMedia d;
  d.trail_slots = static_cast<int>(scene.media.size());
  for (const Medium& m : scene.media) {
    std::vector<double> sigma_t(m.sigma_a.size());
    for (size_t i = 0; i < sigma_t.size(); ++i) sigma_t[i] = m.sigma_a[i] + m.sigma_s[i];
    KMedium k{};
    // A fluorophore's absorption is part of the extinction; its re-emission a collision's branch.
    for (const Fluorophore& f : m.fluorophores) {
      KFluorophore& kf = k.fluorophore[k.fluorophores++];
      kf.absorption = append_spectrum(spectra, f.absorption);
      kf.emission = append_spectrum(spectra, f.e_hat);
      kf.yield = static_cast<float>(f.quantum_yield);
      double sum = 0;
      for (size_t i = 0; i < sigma_t.size(); ++i) sigma_t[i] += f.absorption[i], sum += f.absorption[i];
      kf.absorption_sum = static_cast<float>(sum);
    }
    // A colour grid's spectra are its components' (its mean ones only feed the sums below).
    if (m.components.empty()) {
      k.sigma_t = append_spectrum(spectra, sigma_t);
      k.sigma_s = append_spectrum(spectra, m.sigma_s);
    } else {
      place_components(m, spectra, k, d.trail_slots);
    }
    k.g = static_cast<float>(m.g);
    double sigma_sum = 0, scattered = 0, reemitted = 0;
    for (size_t i = 0; i < sigma_t.size(); ++i) sigma_sum += sigma_t[i], scattered += m.sigma_s[i];
    for (int f = 0; f < k.fluorophores; ++f)
      reemitted += static_cast<double>(k.fluorophore[f].yield) * k.fluorophore[f].absorption_sum;
    k.sigma_mean = sigma_t.empty() ? 0.0f : static_cast<float>(sigma_sum / sigma_t.size());
    k.events = static_cast<float>(scattered + reemitted);
    k.elastic_share = k.events > 0 ? static_cast<float>(scattered / (scattered + reemitted)) : 0.0f;
    k.density = -1;
    if (m.grid) place_grid(*m.grid, spectra, k);
    if (!m.components.empty()) k.density = place_component_grids(m, spectra);
    k.emission = m.emission.empty() ? -1 : append_spectrum(spectra, m.emission);
    place_emission_grids(m, scene.grid, spectra, k);
    if (!m.emission_components.empty()) place_emission_components(m, spectra, k);
    d.media.push_back(k);
  }
  place_medium_lights(scene, light_power, d.media);
  if (!scene.triangle_media.empty())
    for (const KTriangle& t : leaf_triangles) {
      const MediumInterface& mi = scene.triangle_media[t.prim];
      d.tri_media.push_back({mi.inside, mi.outside});
    }
  return d;
}

}  // namespace kasha
