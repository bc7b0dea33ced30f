#include "measure/material_writer.h"

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace kasha {

static nlohmann::json tabulated(const Tabulated& t) {
  return {{"nm", t.nm}, {"value", t.value}};
}

static nlohmann::json grid_summary(const std::vector<double>& nm) {
  return {{"min_nm", nm.front()}, {"max_nm", nm.back()}, {"count", nm.size()}};
}

void write_material_file(const std::string& path, const std::string& name,
                         const MeasuredMaterial& m) {
  nlohmann::json j;
  j["kasha_material"] = 1;
  j["name"] = name;
  if (!m.passive.nm.empty()) j["passive"] = {{"reflectance", tabulated(m.passive)}};
  if (!m.excitation.nm.empty())
    j["fluorescence"] = {{"excitation", tabulated(m.excitation)},
                         {"emission", tabulated(m.emission)}};
  if (m.gloss) {
    j["gloss"] = {{"reflectance", m.gloss->reflectance},
                  {"cone_deg", m.gloss->cone_deg},
                  {"profile", {{"deg", m.gloss->profile_deg}, {"value", m.gloss->profile_value}}}};
  }
  nlohmann::json d;
  d["method"] = m.method;
  d["band_half_width_nm"] = m.band_nm;
  d["band_estimated"] = m.band_estimated;
  d["rank1_relative_residual"] = m.rank1_residual;
  d["rank1_signal_residual"] = m.rank1_signal_residual;
  d["second_order_entries_masked"] = m.second_order_masked;
  d["max_gloss_passive_excitation"] = {{"value", m.max_energy}, {"nm", m.max_energy_nm}};
  d["clipped_nm"] = m.clipped_nm;
  d["excitation_grid"] = grid_summary(m.ex_nm);
  d["emission_grid"] = grid_summary(m.em_nm);
  d["notes"] = m.notes;
  j["diagnostics"] = d;
  write_text_atomically(path, j.dump(1) + "\n");
}

}  // namespace kasha
