#pragma once
// Participating media (docs/media.md): what fills the space between surfaces. A medium has
// spectral absorption σa(λ) and scattering σs(λ) coefficients (per scene unit of length, both
// times "scale"), everywhere (homogeneous) or times a grid of density over a box ("grid",
// pbrt-v4's "uniformgrid"), and a Henyey–Greenstein phase function of asymmetry g. Surfaces
// bound media through their shape's medium interface (the medium inside, behind the front side,
// and outside); a shape that is only a boundary has no material ("interface": true).
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "core/json_node.h"
#include "spectrum/spectrum.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

// The most fluorophores a medium holds (kernels' KASHA_MEDIUM_FLUOROPHORES).
constexpr int kMaxMediumFluorophores = 4;

// A dye dissolved in a medium (docs/media.md#fluorescent-media): its absorption per unit length
// (given as such, or as a molar absorption coefficient times a concentration), the share Φ of the
// absorbed energy it re-emits, isotropically, and the spectrum it re-emits it in.
struct FluorophoreDesc {
  std::string where;
  SpectrumPtr absorption;  // times absorption_scale: per scene unit of length (not the medium's scale)
  double absorption_scale = 1;
  double quantum_yield = 1;
  SpectrumPtr emission;  // any scale: normalized on the grid
};

// A density that scales σa and σs over a box (pbrt-v4's uniformgrid): samples at the centres of
// nx × ny × nz cells spanning [p0, p1] in the medium's space, trilinear between them and 0 beyond
// the outermost ones' neighbours (pbrt-v4's SampledGrid::Lookup), nothing outside the box.
struct DensityGrid {
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> values;  // x fastest: values[(z * ny + y) * nx + x], each ≥ 0
  Eigen::Vector3d p0{0, 0, 0}, p1{1, 1, 1};
  Eigen::Affine3d to_world = Eigen::Affine3d::Identity();  // the medium's space to the world's
  // A VDB grid's own index-to-world map (before the medium's transform), which a temperature
  // grid of the same file must share; the identity for a grid given by its values.
  Eigen::Affine3d file_map = Eigen::Affine3d::Identity();
  // Emission beyond a spectrum (pbrt-v4's emitting grids), on the same samples, empty: none. A
  // scale of the emission per sample (pbrt-v4's "Lescale" grid), and a temperature per sample
  // whose blackbody the medium emits (docs/media.md#emitting-grids).
  std::vector<float> emission_scale, temperature;
  // A colour grid (pbrt-v4's rgbgrid, scene/colour_grid.h): σa's and σs's linear sRGB colour
  // per sample (3 floats each, any size ≥ 0) in place of a density; one list empty: that
  // coefficient is 1 in the whole box; both: not a colour grid.
  std::vector<float> sigma_a_rgb, sigma_s_rgb;
  // An emitting colour grid's radiance Le (pbrt-v4's rgbgrid "Le"): a linear sRGB colour per
  // sample, each pbrt-v4's RGBIlluminantSpectrum; empty: it emits nothing.
  std::vector<float> emission_rgb;
  bool coloured() const { return !sigma_a_rgb.empty() || !sigma_s_rgb.empty(); }
};

// One component of a colour grid as the kernels track it (kernels/media/colour_grid.h).
struct GridComponent {
  std::vector<float> values;             // ρ_k per sample (x fastest); empty: 1 in the whole box
  std::vector<double> sigma_t, sigma_s;  // per bin, times the medium's scale
};

// One component of an emitting colour grid's radiance (kernels/media/medium_emission.h): Le(λ, x)
// = Σ_j ρ_j(x) Le_j(λ), as colour_grid_components splits σa and σs.
struct EmissionComponent {
  std::vector<float> values;     // ρ_j per sample (x fastest)
  std::vector<double> radiance;  // Le_j per bin, times the medium's emission scale
};

// A medium's blackbody emission (pbrt-v4's temperature grids): at a point whose interpolated
// temperature grid value v gives T = (v − offset)·scale above 100 K, it emits σa times the
// blackbody of T normalized to peak 1 (pbrt-v4's BlackbodySpectrum), times its emission scale.
struct Blackbody {
  double offset = 0, scale = 1;
};

// A medium as the scene gives it (JSON "media", pbrt-v4's MakeNamedMedium "homogeneous",
// "uniformgrid", "rgbgrid" and "nanovdb").
struct MediumDesc {
  std::string name;
  std::string where;  // FILE: JSON path of its entry, for messages
  SpectrumPtr sigma_a, sigma_s;
  double scale = 1;
  double g = 0;  // Henyey–Greenstein asymmetry, |g| < 1
  std::vector<FluorophoreDesc> fluorophores;
  std::optional<DensityGrid> grid;  // "grid": σa, σs and the dyes times its density
  SpectrumPtr emission;             // "emission": Le, radiance emitted per unit σa (null: none)
  double emission_scale = 1;        // "emission_scale" given as a number
  std::optional<Blackbody> blackbody;  // "temperature" (its grid in grid->temperature)
};

// A fluorophore on the grid: absorption per bin, and ê (sums to 1 over the bins).
struct Fluorophore {
  std::vector<double> absorption, e_hat;
  double quantum_yield = 1;
};

// On the scene's wavelength grid: per bin, scale·σa and scale·σs, and the fluorophores.
struct Medium {
  std::vector<double> sigma_a, sigma_s;
  double g = 0;
  std::vector<Fluorophore> fluorophores;
  std::optional<DensityGrid> grid;
  // σa·Le per bin (times the grid's density, its emission scale and, with a blackbody, the
  // blackbody's spectrum instead of Le), empty: none.
  std::vector<double> emission;
  std::optional<Blackbody> blackbody;
  // A colour grid's components (its sigma_a and sigma_s are then their mean over the samples),
  // and where it emits its radiance's (its `emission` is then mean σa times mean Le).
  std::vector<GridComponent> components;
  std::vector<EmissionComponent> emission_components;
  // Some collision in it sends light on (σs > 0 in some bin, or a fluorophore) or emits: its
  // collisions are sampled.
  bool scatters() const;
};

// A shape's media (-1: vacuum): inside is behind its front side. A shape whose two media are the
// same is no boundary, and a ray crossing it stays in the medium it was in (pbrt-v4's rule).
struct MediumInterface {
  int inside = -1, outside = -1;
  bool transition() const { return inside != outside; }
};

// One entry of the scene's "media" (an object of named media).
MediumDesc parse_medium(const JsonNode& node, const std::string& name);

// The index of the medium a JSON string names in `media` ("" or null: vacuum, -1).
int medium_index(const JsonNode& node, const std::vector<MediumDesc>& media);

// A shape's "medium": {"inside": NAME, "outside": NAME} (either may be null or left out: vacuum).
MediumInterface parse_medium_interface(const JsonNode& node, const std::vector<MediumDesc>& media);

Medium discretize_medium(const MediumDesc& desc, const WavelengthGrid& grid);

}  // namespace kasha
