#pragma once
// The tables of the scene's alpha cut-outs (kernels/shared/alpha_test.h) as the traversals take
// them on the host: Embree's reference applies the same test in its filter functions, and the
// OpenCL batch traversal uploads them.
#include <vector>

#include "shared/alpha_test.h"

namespace kasha {

struct AlphaCutouts {
  std::vector<KTexcoords> texcoords;  // per triangle, scene order (alpha_texture -1: opaque)
  std::vector<KTexture> textures;     // scalar textures
  std::vector<float> values;          // their images' texels, spectra and matrices
  std::vector<KTexOp> ops;            // texture programs' steps
  bool empty() const { return texcoords.empty(); }
};

}  // namespace kasha
