#pragma once
// Reads a pbrt-v4 scene file into kasha's scene form (the JSON of docs/formats.md#scenes), which
// the scene loader then reads as it reads a .json scene (docs/pbrt-import.md). Everything kasha
// leaves out is one warning with FILE:LINE; what would change the picture's content is an Error.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/json_node.h"

namespace kasha {

// `--material NAME=FILE`: the material named NAME (MakeNamedMaterial), or every shape of the
// object NAME (ObjectBegin), becomes kasha's material file FILE.
struct MaterialOverride {
  std::string name, file;
};

// Whether `path` names a pbrt-v4 scene (by its extension, .pbrt, or .pbrt.gz compressed).
bool is_pbrt_scene(const std::string& path);

// The scene as kasha JSON; relative file names in it are relative to the folder of `path`.
// `sources`, when given, receives the FILE:LINE of the statement behind each shape, material,
// light, texture and the camera, so that errors found in the JSON name the statement.
nlohmann::json import_pbrt_scene(const std::string& path,
                                 const std::vector<MaterialOverride>& overrides = {},
                                 JsonSourceMap* sources = nullptr);

}  // namespace kasha
