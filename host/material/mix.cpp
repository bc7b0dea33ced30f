#include "material/mix.h"

namespace kasha {

MaterialMix parse_mix(const JsonNode& node) {
  MaterialMix mix;
  mix.where = node.where();
  const JsonNode materials = node.at("materials");
  if (!materials.is_array() || materials.size() != 2)
    materials.fail("expected two material names [A, B]");
  for (size_t k = 0; k < 2; ++k) mix.names[k] = materials[k].string();
  if (auto amount = node.find("amount")) {
    if (amount->is_string())
      mix.amount_texture_name = amount->string();
    else
      mix.amount = amount->number_in(0.0, 1.0);
  }
  node.finish();
  return mix;
}

}  // namespace kasha
