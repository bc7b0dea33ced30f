#pragma once
// Textures (docs/textures.md): images (image/rgb_image.h's formats) and checkerboards, looked up at
// a surface's texture coordinates as pbrt-v4 looks them up, applied to a material's passive
// reflectance (a print: the texture multiplies ρ(λ)) or to its excitation (an ink's concentration).
#include <string>
#include <vector>

#include "core/json_node.h"
#include "image/rgb_image.h"
#include "spectrum/spectrum.h"

namespace kasha {

enum class TextureType { image, checkerboard };
enum class TextureWrap { repeat, clamp, black, octahedral_sphere };

struct Texture {
  std::string name, where;  // where: file: JSON path
  TextureType type = TextureType::image;
  // An image: linear sRGB texels, row 0 at the top; "scale" and then "invert" (1 − texel, at
  // least 0) are applied to them as the image is read, as pbrt-v4 applies them to its lookups.
  std::string file;
  RgbImage image;
  ColorEncoding encoding;  // of a PNG's values (image/color_encoding.h)
  double scale = 1;
  bool invert = false;
  bool bilinear = true;
  TextureWrap wrap = TextureWrap::repeat;
  // A checkerboard: its two values, as spectra, and as numbers where they are numbers (-1 not).
  SpectrumPtr even, odd;
  double even_value = -1, odd_value = -1;
  double uscale = 1, vscale = 1, udelta = 0, vdelta = 0;
};

// One entry of the scene's "textures" object.
Texture parse_texture(const JsonNode& node, const std::string& name);

// The textures a scene material carries, by index into the scene's textures (-1: none).
struct MaterialTextures {
  int reflectance = -1, fluorescence = -1;
  std::string where;  // file: JSON path of the material's "textures"
};

}  // namespace kasha
