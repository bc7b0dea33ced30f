#include "colorimetry/as_is_material.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "colorimetry/radiance_factor.h"
#include "core/atomic_file.h"
#include "core/printable.h"

namespace kasha {

// Each bin's value held across the bin, with ramps this wide between bins, so the file resamples
// to the same per-bin values on the grid it was made on (to ~1e-4 of a step).
constexpr double kStepRampNm = 1e-3;

AsIsMaterial as_is_material(const Material& m, const std::vector<double>& lamp,
                            const WavelengthGrid& grid, const std::string& lamp_label) {
  AsIsMaterial r;
  r.lamp = lamp_label;
  const double limit = 1.0 - m.gloss_reflectance();
  RadianceFactor beta = radiance_factor(m, lamp);
  for (int i = 0; i < grid.bins; ++i) {
    double b = beta.reflected[i] + beta.fluorescent[i];
    if (std::isnan(b)) {
      b = beta.reflected[i];
      r.unlit_nm.push_back(grid.center(i));
    }
    if (b > limit) {
      b = limit;
      r.clipped_nm.push_back(grid.center(i));
    }
    r.reflectance.push_back(b);
    const double ramp = grid.bins > 1 ? kStepRampNm : 0.0;
    r.table_nm.push_back(grid.lo(i) + ramp);
    r.table_nm.push_back(grid.hi(i) - ramp);
    r.table_value.push_back(b);
    r.table_value.push_back(b);
  }
  r.desc.name = m.name + " as is under " + lamp_label;
  r.desc.where = "as-is material of '" + m.name + "'";
  r.desc.passive = std::make_shared<PiecewiseLinearSpectrum>(r.table_nm, r.table_value);
  r.desc.gloss = m.gloss;
  return r;
}

static nlohmann::json gloss_json(const GlossDesc& g) {
  nlohmann::json j = {{"reflectance", g.reflectance}};
  if (g.mirror) {
    j["mirror"] = true;
    return j;
  }
  j["cone_deg"] = g.cone_deg;
  if (!g.profile_deg.empty()) j["profile"] = {{"deg", g.profile_deg}, {"value", g.profile_value}};
  return j;
}

void write_as_is_material(const std::string& path, const AsIsMaterial& a,
                          const std::string& source) {
  nlohmann::json j;
  j["kasha_material"] = 1;
  // The lamp's label and the source are command-line bytes: json_text() keeps the JSON UTF-8.
  j["name"] = json_text(a.desc.name);
  j["passive"] = {{"reflectance", {{"nm", a.table_nm}, {"value", a.table_value}}}};
  if (a.desc.gloss) j["gloss"] = gloss_json(*a.desc.gloss);
  j["diagnostics"] = {
      {"method", "as is: the total radiance factor under one lamp as a passive reflectance"},
      {"source", json_text(source)},
      {"lamp", json_text(a.lamp)},
      {"clipped_nm", a.clipped_nm},
      {"unlit_nm", a.unlit_nm},
      {"notes",
       {"each bin's value is held across the bin (ramps of " + std::to_string(kStepRampNm) +
            " nm between bins)",
        "clipped to 1 - gloss where the radiance factor exceeds it (energy conservation)"}}};
  write_text_atomically(path, j.dump(1) + "\n");
}

}  // namespace kasha
