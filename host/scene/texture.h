#pragma once
// Textures (docs/textures.md): images (image/rgb_image.h's formats) and checkerboards, looked up at
// a surface's texture coordinates as pbrt-v4 looks them up, applied to a material's passive
// reflectance (a print: the texture multiplies ρ(λ)) or to its excitation (an ink's concentration).
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "core/json_node.h"
#include "image/rgb_image.h"
#include "spectrum/spectrum.h"

namespace kasha {

// image and checkerboard look up (u, v) alone; the others are textures of textures
// (docs/textures.md#textures-of-textures), as pbrt-v4 has them.
enum class TextureType {
  image,
  checkerboard,
  constant,
  scale,
  mix,
  directionmix,
  bilerp,
  dots,
  fbm,
  wrinkled,
  windy,
  marble
};
enum class TextureWrap { repeat, clamp, black, octahedral_sphere };
// How a 2D texture finds (s, t): pbrt-v4's mappings.
enum class TextureMapping { uv, spherical, cylindrical, planar };

// An operand of a texture of textures: a value (a number or a spectrum) or another texture.
struct TextureInput {
  std::string texture_name;  // "" for a value
  int texture = -1;          // the scene's index, once resolved
  SpectrumPtr spectrum;      // a value (a number is a constant spectrum too)
  double number = 0;
  bool is_number = false;
  std::string where;
};

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
  // Textures of textures: their operands by pbrt-v4's names (tex1, tex2, amount, tex, scale,
  // inside, outside, even, odd, v00, v01, v10, v11).
  std::map<std::string, TextureInput> inputs;
  TextureMapping mapping = TextureMapping::uv;
  Eigen::Affine3d texture_from_world = Eigen::Affine3d::Identity();  // the inverse "transform"
  Eigen::Vector3d v1{1, 0, 0}, v2{0, 1, 0};                          // planar mapping
  Eigen::Vector3d dir{0, 1, 0};  // directionmix: in world space, unit
  int dimension = 2;             // checkerboard
  int octaves = 8;               // fbm, wrinkled, marble
  double roughness = 0.5, marble_scale = 1, variation = 0.2;

  // Whether the kernels evaluate it as a program (everything but a plain (u, v) image or
  // checkerboard of values).
  bool program() const;
};

// One entry of the scene's "textures" object.
Texture parse_texture(const JsonNode& node, const std::string& name);

// Each texture's operands named as the scene's indices; a name no texture has, or a texture
// naming itself in turn, is refused.
void resolve_texture_inputs(std::vector<Texture>& textures);

// The textures a scene material carries, by index into the scene's textures (-1: none).
struct MaterialTextures {
  int reflectance = -1, fluorescence = -1;
  std::string where;    // file: JSON path of the material's "textures"
  int normal_map = -1;  // its "normal_map": the scene's normal_maps index (-1: none)
  std::string normal_map_where;
};

}  // namespace kasha
