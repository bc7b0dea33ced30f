#pragma once
// pbrt-v4's `Texture`, `Material` and `MakeNamedMaterial` as kasha textures and materials
// (docs/pbrt-import.md#materials-and-textures): diffuse, coateddiffuse, coatedconductor,
// diffusetransmission, dielectric, thindielectric, conductor, mix and kasha's own measured
// materials.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "scene/pbrt/pbrt_parameters.h"
#include "scene/pbrt/pbrt_spectra.h"
#include "scene/pbrt/pbrt_textures.h"

namespace kasha {

// The kasha material for pbrt material `type` with `params`; null for a shape that is no surface
// (`interface`, "none": a medium's boundary, left out by the caller with a warning).
nlohmann::json pbrt_material(const std::string& type, const PbrtParameters& params,
                             const PbrtLocation& where, PbrtTextures& textures,
                             const std::filesystem::path& base_dir);

}  // namespace kasha
