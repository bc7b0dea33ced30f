#pragma once
// A stochastic mix of two of the scene's materials (pbrt-v4's MixMaterial;
// docs/materials.md#mixes): at each point of a surface one of them, the second with probability
// `amount`, so an image is in expectation the blend (1 − amount)·first + amount·second.
#include <string>

#include "core/json_node.h"

namespace kasha {

// How deep mixes may nest (a mix of mixes …); the kernels resolve at most this many in turn.
constexpr int kMaxMixDepth = 8;

struct MaterialMix {
  std::string names[2];             // the scene's materials, as written
  int materials[2] = {-1, -1};      // their indices, once the scene resolves the names
  double amount = 0.5;              // in [0, 1]: the second material's share
  std::string amount_texture_name;  // a scene texture whose value is the amount (empty: none)
  int amount_texture = -1;          // its index in the scene's textures
  std::string where;                // for messages
};

// {"materials": [A, B], "amount": NUMBER or TEXTURE}: the names are resolved by the scene.
MaterialMix parse_mix(const JsonNode& node);

}  // namespace kasha
