#pragma once
// pbrt-v4's `Texture` directive as kasha textures (docs/pbrt-import.md#materials-and-textures):
// every class pbrt-v4 has but ptex — imagemap, checkerboard (2D and 3D), constant, scale, mix,
// directionmix, bilerp, dots, fbm, wrinkled, windy, marble — with every 2D mapping (uv,
// spherical, cylindrical, planar) and the texture's own transform.
#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/pbrt/pbrt_parameters.h"
#include "scene/pbrt/pbrt_spectra.h"

namespace kasha {

// A pbrt texture as kasha applies it: a constant, or a kasha texture (by its name in the scene's
// "textures") times a constant factor.
struct PbrtTexture {
  std::string kasha_name;              // empty for a constant
  std::optional<PbrtParameter> value;  // a constant's value (absent: 1), read as its use reads it
  double factor = 1;                   // multiplies the value or the kasha texture
};

struct PbrtTextures {
  std::map<std::string, PbrtTexture> spectrum, scalar;  // pbrt's "spectrum" and "float" textures
  nlohmann::json kasha = nlohmann::json::object();      // the scene's "textures"
  std::vector<std::string> added;  // kasha textures the last definition made (for FILE:LINE)
  bool filter_warned = false;  // an approximated filter is named once per scene, not per texture
};

// Defines texture `name` (`kind` "spectrum" or "float", class `cls`) from its parameters, in the
// space `world_from_texture` (the transform at the directive).
void pbrt_define_texture(const std::string& name, const std::string& kind, const std::string& cls,
                         const PbrtParameters& params, const PbrtLocation& where,
                         const Eigen::Matrix4d& world_from_texture, PbrtTextures& textures,
                         const std::filesystem::path& base_dir);

// The texture a "texture" parameter names among `in` (pbrt's spectrum or float textures).
const PbrtTexture& pbrt_texture_named(const PbrtParameter& p,
                                      const std::map<std::string, PbrtTexture>& in,
                                      const char* kind);

// A constant texture's value as pbrt-v4 reads it where `use` is taken (its SpectrumType).
nlohmann::json pbrt_texture_constant(const PbrtTexture& t, PbrtSpectrumUse use,
                                     const std::filesystem::path& base_dir);

// A float parameter or float texture where kasha takes a number (roughness, thickness, amount):
// a constant texture, or a scale of constants, gives its value; a varying one is refused.
std::optional<double> pbrt_float_value(const PbrtParameters& params, const std::string& name,
                                       const PbrtTextures& textures);

// A kasha texture's name for t (a scale texture of it when its factor is not 1), or "" for a
// constant.
std::string pbrt_kasha_texture(const PbrtTexture& t, PbrtTextures& textures);

}  // namespace kasha
