#include "cli/measure_command.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/output_set.h"
#include "core/printable.h"
#include "material/material.h"
#include "measure/bispectral.h"
#include "measure/fluorimeter.h"
#include "measure/gloss_fit.h"
#include "measure/material_writer.h"
#include "measure/measurement_plots.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

// What measure writes must be a material render takes: read back with the loader it uses, so a
// degenerate measurement fails here naming its input, not later in a scene.
static void check_material_loads(const std::string& file, const std::string& name,
                                 const std::string& source) {
  try {
    MaterialDesc desc = load_material_file(file, name);
    discretize_material(desc, WavelengthGrid{});
  } catch (const std::exception& e) {
    throw Error(source + ": the measured material is not usable: " + e.what());
  }
}

int run_measure(const MeasureArgs& a) {
  std::filesystem::path out(a.output);
  OutputSet outputs;
  for (const auto& [path, option] : {std::pair{a.sample, "--sample"},
                                     {a.etalon, "--etalon"},
                                     {a.etalon_reflectance, "--etalon-reflectance"},
                                     {a.sensitivity, "--sensitivity"},
                                     {a.gloss, "--gloss"},
                                     {a.bispectral, "--bispectral"}})
    outputs.input(path, std::string("the ") + option + " file");
  outputs.file("-o", a.output);
  outputs.directory("--plots", a.plots);
  MeasuredMaterial m;
  if (!a.bispectral.empty()) {
    if (!a.sample.empty() || !a.etalon.empty() || !a.etalon_reflectance.empty() ||
        !a.sensitivity.empty())
      throw Error(
          "measure: --bispectral takes no --sample, --etalon, --etalon-reflectance or "
          "--sensitivity");
    m = material_from_bispectral(read_eem(a.bispectral), a.band_nm);
  } else {
    if (a.sample.empty() || a.etalon.empty() || a.etalon_reflectance.empty())
      throw Error("measure: give --sample, --etalon and --etalon-reflectance (or --bispectral)");
    FluorimeterInput in{
        read_eem(a.sample), read_eem(a.etalon), read_spectrum_csv(a.etalon_reflectance),
        a.sensitivity.empty() ? nullptr : read_spectrum_csv(a.sensitivity), a.band_nm};
    in.etalon_reflectance_source = a.etalon_reflectance;
    in.sensitivity_source = a.sensitivity;
    m = material_from_fluorimeter(in);
  }
  if (!a.gloss.empty()) {
    GlossFit g = fit_gloss(a.gloss, a.cone_deg);
    if (g.gloss.reflectance > 0)
      m.gloss = g.gloss;
    else
      m.notes.push_back("no gloss above the diffuse floor in " + printable(a.gloss));
  }
  check_energy(m, a.clip);

  // The name goes into JSON, which needs UTF-8 (an explicit --name is checked on the command line).
  std::string name = a.name.empty() ? out.stem().string() : a.name;
  if (!valid_utf8(name)) name = printable(name);
  const std::string source =
      !a.bispectral.empty() ? "--bispectral " + a.bispectral : "--sample " + a.sample;
  outputs.write(a.output, [&](const std::string& tmp) {
    write_material_file(tmp, name, m);
    check_material_loads(tmp, name, source);
  });
  if (!a.plots.empty()) write_measurement_plots(outputs.staging(a.plots), m, "--plots " + a.plots);
  outputs.commit();

  std::printf(
      "wrote %s (%s): band ±%.3g nm%s, rank-1 residual %.4f (%.4f where there is signal), max "
      "g+ρ+a %.3f at %g nm%s\n",
      a.output.c_str(), m.method.c_str(), m.band_nm,
      m.band_estimated ? (m.method == "fluorimeter" ? " (from the etalon)" : " (one bin)") : "",
      m.rank1_residual, m.rank1_signal_residual, m.max_energy, m.max_energy_nm,
      m.gloss ? (", gloss " + std::to_string(m.gloss->reflectance)).c_str() : "");
  if (m.rank1_signal_residual > kRank1WarningResidual)
    std::fprintf(stderr,
                 "kasha: warning: rank-1 residual %.3f > %.2f where there is signal: the "
                 "fluorescence is not one emission shape times "
                 "one excitation spectrum (several fluorophores?); the material keeps only its "
                 "best rank-1 part\n",
                 m.rank1_signal_residual, kRank1WarningResidual);
  if (!m.clipped_nm.empty())
    std::fprintf(stderr, "kasha: warning: --clip reduced %zu wavelengths to g + ρ + a = 1\n",
                 m.clipped_nm.size());
  return 0;
}

}  // namespace kasha
