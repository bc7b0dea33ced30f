#pragma once
// Texture programs (docs/textures.md#textures-of-textures): a texture of textures compiled into
// the KTexOp steps that kernels/shared/texture_program.h runs. Scalar textures become steps that
// each write a slot; a spectral texture becomes terms, each a slot (the product of the weights on
// the way down: a mix's 1 − amount and amount, a scale's factor, a checkerboard's or dots' 0/1)
// times a constant spectrum or an image's texels, so the kernels sum spectra linearly and never
// keep a spectrum per node.
#include <functional>
#include <vector>

#include "image/rgb_image.h"
#include "scene/scene.h"
#include "shared/shared_types.h"

namespace kasha {

// Where a program's parts go: the scene's kernel tables, and how to add an image or a spectrum.
struct TextureProgramTables {
  std::vector<KTexOp>& ops;
  std::vector<float>& data;  // the spectra buffer: matrices and constant spectra
  std::function<int(const SpectrumPtr&)> spectrum;       // its binned values' offset in data
  std::function<int(int texture, bool spectral)> image;  // a scene image's plain KTexture
  std::function<int(const RgbImage&)> palette;           // a spectral clamped image's KTexture
};

// The program's root record (KASHA_TEXTURE_PROGRAM) for the scene's texture `texture` used as a
// spectrum (a reflectance) or a number (a concentration, amount or alpha); its steps and terms
// appended to tables.ops. A program over KASHA_TEXTURE_SLOTS slots, or a spectral value where a
// number is needed, is refused naming the texture.
KTexture compile_texture_program(const Scene& scene, int texture, bool spectral,
                                 TextureProgramTables& tables);

// pbrt-v4's marble colour (MarbleTexture::Evaluate) at spline parameter t in [0, 1], linear sRGB.
std::array<double, 3> marble_rgb(double t);

}  // namespace kasha
