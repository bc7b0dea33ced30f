#include "render/render_spec.h"

#include "render/option_table.h"

namespace kasha {

std::string render_fingerprint(const RenderSpec& spec) {
  std::string materials;
  for (const MaterialOverride& m : spec.materials) materials += "|" + m.name + "=" + m.file;
  return spec.scene + "|" + spec.lamp + "|" + spec.integrator + "|" + (spec.spectral ? "1" : "0") +
         settings_fingerprint(spec.settings) + materials;
}

}  // namespace kasha
