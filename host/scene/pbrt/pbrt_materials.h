#pragma once
// pbrt-v4's `Texture`, `Material` and `MakeNamedMaterial` as kasha textures and materials
// (docs/pbrt-import.md#materials-and-textures): diffuse, coateddiffuse, dielectric, conductor, mix
// and kasha's own measured materials; imagemap, checkerboard, scale and constant textures.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "scene/pbrt/pbrt_parameters.h"
#include "scene/pbrt/pbrt_spectra.h"

namespace kasha {

// A pbrt texture as kasha can apply it: a constant, or a kasha texture (an image or a
// checkerboard, by its name in the scene's "textures") times a constant factor.
struct PbrtTexture {
  std::string kasha_name;              // empty for a constant
  std::optional<PbrtParameter> value;  // a constant's value (absent: 1), read as its use reads it
  double factor = 1;                   // multiplies the value or the kasha texture
};

struct PbrtTextures {
  std::map<std::string, PbrtTexture> spectrum, scalar;  // pbrt's "spectrum" and "float" textures
  nlohmann::json kasha = nlohmann::json::object();      // the scene's "textures"
  bool filter_warned = false;  // an approximated filter is named once per scene, not per texture
};

// Defines texture `name` (`kind` "spectrum" or "float", class `cls`) from its parameters.
void pbrt_define_texture(const std::string& name, const std::string& kind, const std::string& cls,
                         const PbrtParameters& params, const PbrtLocation& where,
                         PbrtTextures& textures, const std::filesystem::path& base_dir);

// A constant texture's value as pbrt-v4 reads it where `use` is taken (its SpectrumType).
nlohmann::json pbrt_texture_constant(const PbrtTexture& t, PbrtSpectrumUse use,
                                     const std::filesystem::path& base_dir);

// A float parameter or float texture where kasha takes a number (roughness, thickness, amount):
// a constant texture, or a scale of constants, gives its value; a varying one is refused.
std::optional<double> pbrt_float_value(const PbrtParameters& params, const std::string& name,
                                       const PbrtTextures& textures);

// The kasha material for pbrt material `type` with `params`; null for a shape that is no surface
// (`interface`, "none": a medium's boundary, left out by the caller with a warning).
nlohmann::json pbrt_material(const std::string& type, const PbrtParameters& params,
                             const PbrtLocation& where, const PbrtTextures& textures,
                             const std::filesystem::path& base_dir);

}  // namespace kasha
