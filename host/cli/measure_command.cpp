// `kasha measure`: fluorimeter or bispectral data to a material file
// (docs/measurement.md#the-equations, docs/formats.md#material-files).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
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

struct MeasureArgs {
  std::string sample, etalon, etalon_reflectance, sensitivity, gloss, bispectral, output, plots,
      name;
  double band_nm = 0, cone_deg = 10;
  bool clip = false;
};

// A rank-1 residual (over the entries with signal) above this is reported as a sample that does not
// follow Kasha's rule.
constexpr double kRank1WarningResidual = 0.15;

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

static int run_measure(const MeasureArgs& a) {
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
  const std::string name = a.name.empty() ? json_text(out.stem().string()) : a.name;
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
      printable(a.output).c_str(), m.method.c_str(), m.band_nm,
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

static Command::Action declare_measure(CLI::App& app) {
  auto m = std::make_shared<MeasureArgs>();
  CLI::Option* sample = app.add_option("--sample", m->sample,
                                       "sample excitation–emission matrix (CSV or JASCO export)");
  CLI::Option* etalon = app.add_option(
      "--etalon", m->etalon, "etalon (white diffuse reference) excitation–emission matrix");
  CLI::Option* etalon_reflectance = app.add_option("--etalon-reflectance", m->etalon_reflectance,
                                                   "the etalon's reflectance spectrum (CSV)");
  CLI::Option* sensitivity = app.add_option("--sensitivity", m->sensitivity,
                                            "detector relative spectral sensitivity C(λ) (CSV)");
  app.add_option("--gloss", m->gloss, "goniometer CSV: theta_in_deg, theta_out_deg, brdf");
  app.add_option("--band-nm", m->band_nm,
                 "half-width of the near-diagonal band (default: from the etalon)")
      ->check(cli::positive_number(1000));
  app.add_option("--cone-deg", m->cone_deg, "gloss cone around the mirror direction")
      ->check(cli::number_within(0.1, 90.0));
  app.add_option("--bispectral", m->bispectral, "a measured bispectral (Donaldson) matrix instead")
      ->excludes(sample)
      ->excludes(etalon)
      ->excludes(etalon_reflectance)
      ->excludes(sensitivity);
  app.add_option("-o,--output", m->output, "material JSON to write")->required();
  app.add_option("--plots", m->plots, "write the method's figures (PNG) into this directory");
  app.add_option("--name", m->name, "material name (default: the output file's stem)")
      ->check(cli::utf8_text());
  app.add_flag("--clip", m->clip, "clip an energy gain instead of failing, and record it");
  app.callback([m] {
    if (m->bispectral.empty() &&
        (m->sample.empty() || m->etalon.empty() || m->etalon_reflectance.empty()))
      throw CLI::ValidationError(
          "measure", "give --sample, --etalon and --etalon-reflectance (or --bispectral)");
  });
  return [m] { return run_measure(*m); };
}

KASHA_REGISTER_COMMAND(measure, "measure",
                       "turn fluorimeter or bispectral data into a material file", 4, false,
                       declare_measure);

}  // namespace kasha
