#include "render/render_settings.h"

#include <cstdio>

#include "core/error.h"

namespace kasha {

namespace {
using V = RenderSetting::Value;
// Where a setting lives in IntegratorSettings.
#define FIELD(member) [](IntegratorSettings& s) -> SettingField { return &s.member; }
constexpr double kMaxInt = 2147483647;
}  // namespace

const std::vector<RenderSetting>& render_settings() {
  // clang-format off: a table, a setting a row
  static const std::vector<RenderSetting> table = {
    {"--spp", "camera samples per pixel per pass (default 16; photon mapping 8; vcm, bpt 8, 4 where "
     "mirrors, glass or smooth coats are, vcm 2 where caustics light most of what the camera "
     "sees; ppm 1)",
     V::integer, 1, 1 << 20, {}, false, false, FIELD(spp)},
    {"--photons",
     "photons per pass (default 2^18; vcm, bpt, ppm: light subpaths, one a pixel, ppm at least "
     "2^16, vcm 32 a pixel where caustics light most of what the camera sees)",
     V::integer, 1, kMaxInt, {}, false, false, FIELD(photons)},
    {"--alpha", "photon mapping, vcm, ppm: radius reduction α (default 0.8)",
     V::number, 0.01, 0.99, {}, false, false, FIELD(alpha)},
    {"--radius", "photon mapping, vcm, ppm: initial gather radius (default: from the pixel footprint)",
     V::positive, 0, 1e300, {}, false, false, FIELD(radius)},
    {"--edge-correction",
     "photon mapping, vcm, ppm: divide the density by the measured fraction of the gather discs "
     "on accepted surface (default; --edge-correction=false leaves it out)",
     V::flag, 0, 0, {}, false, false, FIELD(edge_correction)},
    {"--gather",
     "photon mapping: gather on the device (a hashed grid) or on the host (nanoflann); default "
     "auto: the device",
     V::choice, 0, 0, {"auto", "device", "host"}, false, false, FIELD(gather)},
    {"--memory",
     "photon mapping: memory for the photon store, bytes with an optional unit (512MiB, 2GB); "
     "default: a quarter of the device's memory (an eighth on a CPU)",
     V::bytes, 1, 1125899906842624.0 /* 2^50 */, {}, false, /*device's own*/ true, FIELD(memory)},
    {"--merges",
     "vcm: merge at the first camera vertex that is not delta only the light that came through a "
     "mirror or glass (caustic), all light there (first, as SPPM gathers), or all light at every "
     "such vertex (every, Georgiev et al.'s VCM); default auto: first where caustics light most "
     "of what the camera sees, else caustic",
     V::choice, 0, 0, {"auto", "caustic", "first", "every"}, false, false, FIELD(merges)},
    {"--view", "debug view: emission, normals or albedo",
     V::choice, 0, 0, {"emission", "normals", "albedo"}, false, false, FIELD(view)},
    {"--seed", "random seed", V::integer, 0, 4294967295.0, {}, /*common*/ true, false, FIELD(seed)},
    {"--max-depth",
     "safety limit on path length in vertices (default 262144, far beyond what Russian "
     "roulette reaches); what it cuts is reported",
     V::integer, 1, 1 << 30, {}, /*common*/ true, false, FIELD(max_depth)},
    {"--sampler", "sobol (default: Owen-scrambled Sobol points) or independent (PCG streams)",
     V::choice, 0, 0, {"sobol", "independent"}, /*common*/ true, false, FIELD(sampler)},
  };
  // clang-format on
  return table;
}

const RenderSetting& render_setting(const std::string& name) {
  for (const RenderSetting& s : render_settings())
    if (s.name == name) return s;
  throw Error("no render setting " + name);
}

std::string settings_fingerprint(const IntegratorSettings& settings) {
  IntegratorSettings s = settings;  // the table's fields are writable ones
  std::string text;
  for (const RenderSetting& setting : render_settings()) {
    if (setting.device_own) continue;
    text += "|";
    std::visit(
        [&](auto* value) {
          using T = std::remove_pointer_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::string>) {
            text += *value;
          } else {
            char number[32];
            std::snprintf(number, sizeof number, "%.17g", static_cast<double>(*value));
            text += number;
          }
        },
        setting.field(s));
  }
  return text;
}

}  // namespace kasha
