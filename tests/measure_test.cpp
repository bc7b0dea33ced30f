// `kasha measure` against a simulated fluorimeter with known answers, the real Post-it matrix,
// gloss from a simulated goniometer, and bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/csv_table.h"
#include "material/material.h"
#include "measure/bispectral.h"
#include "measure/fluorimeter.h"
#include "measure/gloss_fit.h"
#include "simulated_instrument.h"
#include "spectrum/spectrum_parser.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// The etalon's reflectance as a spectrum, as `--etalon-reflectance` would read it.
SpectrumPtr etalon_spectrum() {
  std::vector<double> nm, v;
  for (double l = 250; l <= 850; l += 5) nm.push_back(l), v.push_back(etalon_rho()(l));
  return make_tabulated_spectrum(nm, v, "etalon");
}

SpectrumPtr sensitivity_spectrum(const Instrument& in) {
  std::vector<double> nm, v;
  for (double l = 250; l <= 850; l += 1) nm.push_back(l), v.push_back(in.sensitivity(l));
  return make_tabulated_spectrum(nm, v, "sensitivity");
}

MeasuredMaterial measure(const Instrument& in, const TrueMaterial& truth, bool give_sensitivity) {
  FluorimeterInput input{in.measure(truth, nullptr, "sample.csv"),
                         in.measure(TrueMaterial{}, etalon_rho(), "etalon.csv"), etalon_spectrum(),
                         give_sensitivity ? sensitivity_spectrum(in) : nullptr, 0.0};
  return material_from_fluorimeter(input);
}

std::string instrument_files(const Instrument& in, const TrueMaterial& truth) {
  return write_instrument_files(scratch_dir().string(), in, truth);
}

void expect_recovered(const MeasuredMaterial& m, const TrueMaterial& truth) {
  double worst_rho = 0, worst_a = 0, l1 = 0;
  for (size_t k = 0; k < m.passive.nm.size(); ++k) {
    worst_rho = std::max(worst_rho, std::abs(m.passive.value[k] - truth.rho(m.passive.nm[k])));
  }
  for (size_t k = 0; k < m.excitation.nm.size(); ++k)
    worst_a =
        std::max(worst_a, std::abs(m.excitation.value[k] - truth.excitation(m.excitation.nm[k])));
  for (size_t k = 0; k + 1 < m.emission.nm.size(); ++k) {
    double h = m.emission.nm[k + 1] - m.emission.nm[k];
    l1 += 0.5 * h *
          (std::abs(m.emission.value[k] - truth.emission(m.emission.nm[k])) +
           std::abs(m.emission.value[k + 1] - truth.emission(m.emission.nm[k + 1])));
  }
  EXPECT_LT(worst_rho, 0.01);
  EXPECT_LT(worst_a, 0.02);
  EXPECT_LT(l1, 0.05);
  EXPECT_LT(m.rank1_signal_residual, 0.15);
  std::printf(
      "  band ±%.1f nm, max |Δρ| %.4f, max |Δa| %.4f, emission L1 %.4f, residual %.3f (signal "
      "%.3f)\n",
      m.band_nm, worst_rho, worst_a, l1, m.rank1_residual, m.rank1_signal_residual);
}

}  // namespace

TEST(Measure, RecoversAKnownMaterialWithSensitivity) {
  Instrument in = Instrument::typical(true);
  MeasuredMaterial m = measure(in, brightened_paper(), true);
  expect_recovered(m, brightened_paper());
  EXPECT_GT(m.second_order_masked, 0);
  // The band comes from the etalon's peak: wider than the excitation band-pass's half width.
  EXPECT_GT(m.band_nm, 4);
  EXPECT_LT(m.band_nm, 20);
}

TEST(Measure, RecoversAKnownMaterialFromACorrectedInstrument) {
  Instrument in = Instrument::typical(false);
  expect_recovered(measure(in, brightened_paper(), false), brightened_paper());
}

TEST(Measure, IgnoringTheSensitivityIsCaught) {
  // The same data without --sensitivity: every f^f entry is off by C(λo)/C(λi), so the yield
  // (C(370)/C(445) ≈ 1.14 here) and the emission shape come out wrong.
  Instrument in = Instrument::typical(true);
  MeasuredMaterial m = measure(in, brightened_paper(), false);
  double worst_a = 0, l1 = 0;
  for (size_t k = 0; k < m.excitation.nm.size(); ++k)
    worst_a = std::max(worst_a, std::abs(m.excitation.value[k] -
                                         brightened_paper().excitation(m.excitation.nm[k])));
  for (size_t k = 0; k + 1 < m.emission.nm.size(); ++k)
    l1 += (m.emission.nm[k + 1] - m.emission.nm[k]) *
          std::abs(m.emission.value[k] - brightened_paper().emission(m.emission.nm[k]));
  EXPECT_GT(worst_a, 0.03);
  EXPECT_GT(l1, 0.03);
}

TEST(Measure, TwoFluorophoresAreFlagged) {
  TrueMaterial two = brightened_paper();
  two.rho = [](double) { return 0.5; };
  two.excitation = [](double l) { return 0.2 * gaussian(l, 350, 40); };
  two.excitation2 = [](double l) { return 0.25 * gaussian(l, 520, 40); };
  two.emission2 = emission_gaussian(610, 40);
  Instrument in = Instrument::typical(true);
  MeasuredMaterial m = measure(in, two, true);
  EXPECT_GT(m.rank1_signal_residual, 0.3);

  // End to end: the command warns on stderr and still writes the material.
  std::string d = scratch_dir().string();
  auto r = run_kasha("measure " + instrument_files(in, two) + " -o " + d + "/two.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("kasha: warning: rank-1 residual"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(d + "/two.json"));
}

TEST(Measure, CommandWritesALoadableMaterialAndPlots) {
  Instrument in = Instrument::typical(true);
  std::string d = scratch_dir().string();
  auto r = run_kasha("measure " + instrument_files(in, brightened_paper()) + " -o " + d +
                     "/paper.json --plots " + d + "/plots");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  MaterialDesc desc = load_material_file(d + "/paper.json", "");
  EXPECT_EQ(desc.name, "paper");
  Material mat = discretize_material(desc, WavelengthGrid{300, 10, 48});
  EXPECT_TRUE(mat.fluorescent());
  EXPECT_NEAR(mat.a[7], 0.3, 0.02);  // the bin 370–380 nm
  for (const char* png : {"raw_matrix.png", "offband_matrix.png", "passive.png", "excitation.png",
                          "emission.png", "fit_residual.png"})
    EXPECT_GT(std::filesystem::file_size(d + "/plots/" + png), 1000u) << png;
}

TEST(Measure, RealPostItBispectralMatrix) {
  ExcitationEmissionMatrix D = read_eem(
      source_path("scenes/data/Labsphere_BFC450_3M_PostIt_fluorescent_yellow_donaldson_10nm.csv"));
  MeasuredMaterial m = material_from_bispectral(D, 0);
  // A yellow fluorescent dye: excited in the blue, emitting green-yellow, reflecting yellow and
  // red.
  auto peak = [](const Tabulated& t) {
    return t.nm[std::max_element(t.value.begin(), t.value.end()) - t.value.begin()];
  };
  EXPECT_NEAR(peak(m.excitation), 460, 30);
  EXPECT_NEAR(peak(m.emission), 520, 30);
  EXPECT_LT(interpolate(m.passive, 450), 0.2);
  EXPECT_GT(interpolate(m.passive, 650), 0.85);
  EXPECT_LT(m.rank1_signal_residual, 0.1);  // Kasha's rule holds where there is signal
  double sum = 0;
  for (size_t k = 0; k < m.emission.nm.size(); ++k) sum += m.emission.value[k] * 10;
  EXPECT_NEAR(sum, 1.0, 1e-9);
  check_energy(m, false);
  EXPECT_LE(m.max_energy, 1.0);
}

TEST(Measure, GlossFromASimulatedGoniometer) {
  // brdf = ρ/π + g·p(δ)/cos θo with p ∝ a 3°-wide gaussian in δ inside a 10° cone.
  const double g = 0.06, rho = 0.4, sigma = 3 * M_PI / 180;
  double norm = 0;  // 2π ∫ exp(-δ²/2σ²) sin δ dδ over the cone
  for (int k = 0; k < 10000; ++k) {
    double d = (k + 0.5) * (10 * M_PI / 180) / 10000;
    norm +=
        2 * M_PI * std::exp(-d * d / (2 * sigma * sigma)) * std::sin(d) * (10 * M_PI / 180) / 10000;
  }
  std::ofstream f(scratch_dir() / "gonio.csv");
  f << "theta_in_deg,theta_out_deg,brdf\n";
  for (double ti : {20.0, 45.0})
    for (double to = -80; to <= 80; to += 0.5) {
      double d = std::abs(to - ti) * M_PI / 180;
      double p = d <= 10 * M_PI / 180 ? std::exp(-d * d / (2 * sigma * sigma)) / norm : 0.0;
      f << ti << "," << to << "," << rho / M_PI + g * p / std::cos(to * M_PI / 180) << "\n";
    }
  f.close();
  GlossFit fit = fit_gloss((scratch_dir() / "gonio.csv").string(), 10);
  EXPECT_NEAR(fit.gloss.reflectance, g, 0.002);
  EXPECT_NEAR(fit.diffuse_floor, rho / M_PI, 1e-6);
  EXPECT_EQ(fit.incidence_angles, 2);
  EXPECT_EQ(fit.gloss.profile_deg.front(), 0);
  EXPECT_LE(fit.gloss.profile_deg.back(), 10);
}

TEST(Measure, BadInputsGiveOneLineAndNoMaterial) {
  Instrument in = Instrument::typical(false);
  std::string d = scratch_dir().string();
  write_eem_csv(d + "/s.csv", in.measure(brightened_paper(), nullptr, "s.csv"));
  write_eem_csv(d + "/e.csv", in.measure(TrueMaterial{}, etalon_rho(), "e.csv"));
  std::ofstream(d + "/rho.csv") << "nm,rho\n250,0.97\n850,0.98\n";
  std::ofstream(d + "/negative.csv") << "nm,rho\n250,0.97\n500,-0.1\n850,0.98\n";
  // A coarser etalon grid.
  Instrument coarse = in;
  coarse.ex_nm.clear();
  for (double l = 300; l <= 600; l += 10) coarse.ex_nm.push_back(l);
  write_eem_csv(d + "/coarse.csv", coarse.measure(TrueMaterial{}, etalon_rho(), "coarse.csv"));
  // An etalon with a dead column.
  ExcitationEmissionMatrix dead = in.measure(TrueMaterial{}, etalon_rho(), "dead.csv");
  dead.value.col(20).setZero();
  write_eem_csv(d + "/dead.csv", dead);
  // A non-numeric cell.
  std::ofstream(d + "/text.csv") << "em\\ex,400,410\n400,1,2\n410,3,oops\n";

  std::string out = d + "/m.json";
  auto check = [&](const std::string& args, const std::string& expected) {
    auto r = run_kasha("measure " + args + " -o " + out);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  };
  std::string good =
      "--sample " + d + "/s.csv --etalon " + d + "/e.csv --etalon-reflectance " + d + "/rho.csv";
  check("--sample " + d + "/s.csv --etalon " + d + "/coarse.csv --etalon-reflectance " + d +
            "/rho.csv",
        "grids do not match");
  check(good + " --band-nm 0.5", "empty band: no emission sample lies within");
  check(
      "--sample " + d + "/s.csv --etalon " + d + "/dead.csv --etalon-reflectance " + d + "/rho.csv",
      "the etalon reading is zero in the band at excitation 400 nm");
  check("--sample " + d + "/s.csv --etalon " + d + "/e.csv --etalon-reflectance " + d +
            "/negative.csv",
        "negative.csv: line 3: at 500 nm: negative value -0.1");
  check(
      "--sample " + d + "/text.csv --etalon " + d + "/e.csv --etalon-reflectance " + d + "/rho.csv",
      "text.csv: line 3, column 3: not a number: \"oops\"");
  check("--sample " + d + "/s.csv", "give --sample, --etalon and --etalon-reflectance");
  check("--bispectral " + d + "/missing.csv", "missing.csv: cannot open file");
  // An energy gain fails without --clip, and is clipped and recorded with it.
  TrueMaterial hot = brightened_paper();
  hot.rho = [](double) { return 0.9; };
  write_eem_csv(d + "/hot.csv", in.measure(hot, nullptr, "hot.csv"));
  std::string hot_args =
      "--sample " + d + "/hot.csv --etalon " + d + "/e.csv --etalon-reflectance " + d + "/rho.csv";
  check(hot_args, "energy gain at ");
  auto r = run_kasha("measure " + hot_args + " --clip -o " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream written(out);
  nlohmann::json j = nlohmann::json::parse(written);
  EXPECT_FALSE(j["diagnostics"]["clipped_nm"].empty());
}

TEST(Measure, JascoExportsAreReadAsSpectraAndMatrices) {
  // Real exports: tab-separated with CRLF and a Shift-JIS footer, and a comma CSV; descending x.
  CsvTable t = read_csv_table(
      source_path("tests/data/JASCOFiles.jl_uvvis_test_V-730_tab_export_SJIS_footer.txt"));
  ASSERT_EQ(t.rows.size(), 1001u);
  EXPECT_EQ(t.fields["XUNITS"], "NANOMETERS");
  EXPECT_EQ(t.rows.front()[0], 1000);
  std::string err = error_of([&] {
    read_spectrum_csv(source_path("tests/data/JASCOFiles.jl_uvvis_abs_V-730_tab_export.txt"));
  });
  EXPECT_NE(err.find("at 400 nm: negative value"), std::string::npos)
      << err;  // absorbance, not a spectrum
  err = error_of(
      [&] { read_spectrum_csv(source_path("tests/data/JASCOFiles.jl_raman_japanese_test.csv")); });
  EXPECT_NE(err.find("x units are 1/CM"), std::string::npos) << err;
  // A 3-D export: the first XYDATA row holds the excitation wavelengths; x descending.
  std::string path =
      write_file("jasco3d.txt",
                 "TITLE\tEEM\r\nXUNITS\tNANOMETERS\r\nNPOINTS\t3\r\nXYDATA\r\n\t350\t360\r\n"
                 "420\t0.5\t0.25\r\n410\t1.5\t1.25\r\n400\t2\t3\r\n\r\n[footer]\tx\r\n");
  ExcitationEmissionMatrix m = read_eem(path);
  ASSERT_EQ(m.ex_nm.size(), 2u);
  EXPECT_EQ(m.em_nm, (std::vector<double>{400, 410, 420}));
  EXPECT_EQ(m.value(0, 1), 3);
  EXPECT_EQ(m.value(2, 0), 0.5);
}

// scenes/materials/brightened_paper.json is what its note (scenes/materials/SOURCES.md) says: the
// simulated fluorimeter's files for the brightened paper through `kasha measure`.
TEST(Measure, ShippedBrightenedPaperIsReproduced) {
  const std::string d = scratch_dir().string();
  auto r = run_kasha(
      "measure " + write_instrument_files(d, Instrument::visible_scan(), brightened_paper()) +
      " -o " + d + "/paper.json --name \"Brightened paper (simulated fluorimeter)\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json made = nlohmann::json::parse(std::ifstream(d + "/paper.json"));
  nlohmann::json shipped =
      nlohmann::json::parse(std::ifstream(source_path("scenes/materials/brightened_paper.json")));
  EXPECT_EQ(made["name"], shipped["name"]);
  for (const char* part :
       {"/passive/reflectance", "/fluorescence/excitation", "/fluorescence/emission"}) {
    const auto& a = made[nlohmann::json::json_pointer(part)];
    const auto& b = shipped[nlohmann::json::json_pointer(part)];
    ASSERT_EQ(a["nm"], b["nm"]) << part;
    for (size_t k = 0; k < a["value"].size(); ++k)
      EXPECT_NEAR(a["value"][k].get<double>(), b["value"][k].get<double>(), 1e-9) << part << k;
  }
}
