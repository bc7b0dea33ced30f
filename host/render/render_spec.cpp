#include "render/render_spec.h"

#include <string>

#include "render/option_table.h"

namespace kasha {

std::string render_fingerprint(const RenderSpec& spec) {
  std::string materials;
  for (const MaterialOverride& m : spec.materials) materials += "|" + m.name + "=" + m.file;
  return spec.scene + "|" + spec.lamp + "|" + spec.integrator + "|" + (spec.spectral ? "1" : "0") +
         settings_fingerprint(spec.settings) + materials + "|" + std::to_string(spec.bin_nm);
}

std::optional<GridRequest> RenderSpec::grid() const {
  return bins_request(bin_nm);
}

}  // namespace kasha
