#include "render/render_spec.h"

namespace kasha {

std::string render_fingerprint(const RenderSpec& spec) {
  return spec.scene + "|" + spec.lamp + "|" + spec.integrator + "|" + (spec.spectral ? "1" : "0") +
         settings_fingerprint(spec.settings);
}

}  // namespace kasha
