#pragma once
// The surface model of docs/design.md#the-surface-model: white gloss lobe + coloured Lambert
// passive part + Lambert fluorescent part e(λo)·a(λi)/π; or a smooth dielectric or conductor
// interface (docs/materials.md). MaterialDesc is the continuous description as read; Material is
// the same on a wavelength grid, checked for energy conservation.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/json_node.h"
#include "material/coat.h"
#include "material/mix.h"
#include "spectrum/spectrum.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

struct GlossDesc {
  double reflectance = 0;  // g, white
  double cone_deg = 10;    // the lobe is zero outside this cone around the mirror direction
  bool mirror = false;     // ideal mirror (delta lobe)
  // p as a function of the angle from the mirror direction; empty for a uniform cone.
  std::vector<double> profile_deg, profile_value;
};

// What a material is (KASHA_KIND_* in the kernels); a mix picks one of two others per point.
// interface: no surface at all, only the boundary of media (a shape's "interface": true).
enum class MaterialKind { measured, dielectric, conductor, mix, interface };

// A smooth dielectric interface: eta is the index on the back side of its surfaces over the
// index on the front side (1.5: glass in air; below 1: an air bubble in water or glass).
// With a spectral index (`eta_spectrum`), the dielectric disperses (docs/materials.md#dispersion).
struct DielectricDesc {
  double eta = 1.5;          // a constant index
  SpectrumPtr eta_spectrum;  // or one that varies with wavelength
  // A thin sheet (pbrt-v4's ThinDielectricBxDF): its two interfaces' every round trip summed,
  // light reflects with R' = R + T²R / (1 − R²) or passes straight through.
  bool thin = false;
};

// GGX roughness of a dielectric or conductor (docs/materials.md#rough-surfaces): pbrt-v4's
// "roughness" (or "uroughness" and "vroughness"), remapped to alpha = sqrt(roughness) unless
// "remap_roughness" is false. Below alpha 1e-3 the surface is smooth.
struct Roughness {
  double alpha_x = 0, alpha_y = 0;
  // An axis may take a scalar texture's value instead, per point, remapped as a number is
  // (pbrt-v4's "texture roughness"): "" for the number; the index once the scene resolves it.
  std::string texture_name[2];
  int texture[2] = {-1, -1};
  bool remap = true;
  std::string where[2];        // of each textured key, for messages
  bool may_be_smooth = false;  // textured: some point may be smooth (set by the scene)
  bool textured() const { return !texture_name[0].empty() || !texture_name[1].empty(); }
  // A textured axis may be smooth at some points and rough at others: the kernels decide per
  // point, and everything else takes the material as rough.
  bool rough() const { return textured() || std::max(alpha_x, alpha_y) >= 1e-3; }
  bool anisotropic() const {
    return texture_name[0] != texture_name[1] || (!textured() && alpha_x != alpha_y);
  }
};

// A smooth conductor: complex index eta + i k over the outside medium's (air).
struct ConductorDesc {
  std::string metal;  // a built-in table's name (material/metals.h), or empty for user spectra
  SpectrumPtr eta, k;
};

struct MaterialDesc {
  std::string name;
  std::string where;  // "file: /json/path", for messages
  MaterialKind kind = MaterialKind::measured;
  DielectricDesc dielectric;
  ConductorDesc conductor;
  Roughness roughness;     // a dielectric's or conductor's
  SpectrumPtr passive;     // ρ(λ)
  SpectrumPtr excitation;  // a(λ)
  SpectrumPtr emission;    // e(λ), any scale: normalized on the grid
  // Lambert transmission τ(λ) to the other side (pbrt-v4's diffusetransmission): the passive part
  // reflects ρ, this part transmits τ; `transmission_scale` multiplies both.
  SpectrumPtr transmittance;
  double transmission_scale = 1;
  std::optional<GlossDesc> gloss;
  std::optional<CoatDesc> coat;    // a dielectric coat over the Lambert parts or the conductor
  std::optional<MaterialMix> mix;  // kind mix: its two materials and amount
  // A rough layered metal's parts (material/layered_metal.h), which the scene makes: the metal
  // under the coat (a conductor), and both parts' reflectance over the share they are chosen at.
  bool under_coat = false;
  double layer_scale = 1;
  double layered_alpha = 0;  // the metal's own GGX alpha (isotropic mean) under the coat

  bool fluorescent() const { return excitation != nullptr; }
};

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::measured;
  double eta = 1;                  // a dielectric's constant index
  bool thin = false;               // a thin dielectric sheet (DielectricDesc::thin)
  std::vector<double> eta_bins;    // a dispersive dielectric's, per bin (empty: constant)
  std::vector<double> eta_c, k_c;  // a conductor's, per bin
  Roughness roughness;
  std::vector<double> rho;    // empty without a passive part
  std::vector<double> tau;    // Lambert transmittance; empty without one
  std::vector<double> a;      // empty without fluorescence
  std::vector<double> e_hat;  // e·Δλ, sums to 1; empty without fluorescence
  std::optional<GlossDesc> gloss;
  std::optional<CoatDesc> coat;
  std::optional<MaterialMix> mix;  // kind mix (its indices set by the scene)
  bool under_coat = false;         // MaterialDesc::under_coat
  double layer_scale = 1;          // MaterialDesc::layer_scale
  // A layered metal's Lambert part: its own t(μ) at kCoatTableSize cosines, no internal
  // reflectance (its ρ is the layer's light per bin already); empty otherwise.
  std::vector<double> lambert_transmission;

  bool fluorescent() const { return !a.empty(); }
  bool transmissive() const { return !tau.empty(); }
  bool specular() const {
    return kind == MaterialKind::dielectric || kind == MaterialKind::conductor;
  }
  bool dispersive() const { return !eta_bins.empty(); }
  bool rough() const { return specular() && roughness.rough(); }
  double gloss_reflectance() const { return gloss ? gloss->reflectance : 0.0; }
};

// A material object (inline in a scene, or the root of a material file).
MaterialDesc parse_material(const JsonNode& node, const std::string& name);
// Puts a coat ({"eta", "thickness", "roughness"}: docs/materials.md#coated-surfaces) over the
// material's Lambert parts, or a smooth one over a smooth conductor
// (docs/materials.md#coated-conductors); a gloss part or a dielectric is refused.
void apply_coat(MaterialDesc& material, const JsonNode& coat);
// A material file written by `kasha measure` or by hand: {"kasha_material": 1, ...}.
MaterialDesc load_material_file(const std::string& path, const std::string& name);
// Resamples to the grid, normalizes the emission and checks g + ρ + a <= 1 in every bin; the
// error names the material and the wavelength.
Material discretize_material(const MaterialDesc& desc, const WavelengthGrid& grid);

}  // namespace kasha
