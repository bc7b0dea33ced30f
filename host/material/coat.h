#pragma once
// A smooth dielectric coat over a material's Lambert parts (docs/materials.md#coated-surfaces):
// pbrt-v4's coateddiffuse with a smooth interface and a non-scattering layer (albedo 0) of optical
// depth `thickness` along the normal. A Lambert base makes the light under the coat diffuse after
// its first bounce, so the bounces between coat and base sum to a geometric series in two numbers
// per coat: the internal reflectance R̄ and the mean transmittance τ̄ below.
#include <string>
#include <vector>

namespace kasha {

struct CoatDesc {
  double eta = 1.5;         // the coat's index over the outside's (pbrt-v4's default)
  double thickness = 0.01;  // optical depth along the normal (pbrt-v4's default)
  double alpha = 0;         // GGX roughness of its interface (isotropic); below 1e-3: smooth
  // A roughness texture's name (pbrt-v4's "texture roughness" on a coat): the coat's tables take
  // one roughness, so the scene sets alpha from the texture's mean (scene.cpp).
  std::string alpha_texture, alpha_where;
  bool alpha_remap = true;
  bool rough() const { return alpha >= 1e-3; }
};

// Fresnel reflectance of a smooth dielectric interface for unpolarized light, cos_i on the side
// the light arrives from, eta the far side's index over the near side's; 1 under total internal
// reflection.
double fresnel_dielectric(double cos_i, double eta);

// t(θ) = (1 − F(θ))·exp(−thickness / cos θt): light arriving from outside at cos θ that reaches
// the base (θt its angle inside), and by reciprocity the share of the base's light leaving at θ.
double coat_transmission(const CoatDesc& coat, double cos_theta);

// R̄ = ∫ F_inside(θ) exp(−2 thickness / cos θ) cos θ dω / π over the hemisphere under the coat:
// of the light the base sends up, the share that comes back down to it (total internal reflection
// included).
double coat_internal_reflectance(const CoatDesc& coat);

// τ̄ = ∫ t(θ) cos θ dω / π over the outside hemisphere: with 1/η² the diffuse part's albedo per
// unit of its outgoing transmission.
double coat_mean_transmission(const CoatDesc& coat);

// A rough coat (GGX, single scattering as pbrt-v4's rough DielectricBxDF) in the same form: with
// E(μ) the albedo of its reflection lobe and T(μ) its transmittance (both for light from
// outside at cos θ = μ), t(μ) = T(μ)·exp(−thickness / μt) with μt the smooth refraction's cosine;
// R̄ from the lobe's albedo from inside. Tabulated at μ = k / (kCoatTableSize − 1).
constexpr int kCoatTableSize = 64;
struct CoatTables {
  std::vector<double> reflect;   // E(μ)
  std::vector<double> transmit;  // t(μ)
  double internal = 0;           // R̄
  double mean = 0;               // τ̄ = ∫ t(μ) 2μ dμ
};
CoatTables rough_coat_tables(const CoatDesc& coat);

// A coat table's value at μ: linear between its kCoatTableSize nodes, as the kernels read it
// (kernels/materials/coat.h); and ∫₀¹ t(μ) 2μ dμ of a table read so.
double coat_table_at(const std::vector<double>& table, double mu);
double coat_table_mean(const std::vector<double>& table);

}  // namespace kasha
