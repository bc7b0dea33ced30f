// `kasha colorimetry` against values worked by hand from the CIE tables, published CIELAB,
// whiteness and CIEDE2000 examples (Sharma, Wu and Dalal 2005), the "as is" material, the command
// line, and renders: a flat sample under a uniformly emitting black hemisphere (no interreflection)
// must show colorimetry's XYZ in every physical integrator.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "color/cie_observer.h"
#include "colorimetry/cie_lab.h"
#include "colorimetry/ciede2000.h"
#include "colorimetry/sample_colorimetry.h"
#include "colorimetry/whiteness.h"
#include "core/csv_table.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/spectrum_argument.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

MaterialDesc material_from_json(const std::string& json) {
  return parse_material(JsonNode::from_json(nlohmann::json::parse(json), "test.json"), "test");
}

// ∫ cmf over [lo, hi] by the trapezoid rule on the 1 nm CIE table, read here from the CSV, apart
// from kasha's own resampling (integer bounds: exact for the table's linear interpolation).
struct CmfIntegrals {
  std::vector<std::vector<double>> rows;
  explicit CmfIntegrals(const std::string& file) {
    rows = read_csv_table(source_path("host/data/" + file)).rows;
  }
  double integral(int k, double lo, double hi) const {
    double sum = 0;
    for (size_t r = 0; r + 1 < rows.size(); ++r)
      if (rows[r][0] >= lo && rows[r + 1][0] <= hi) sum += 0.5 * (rows[r][k] + rows[r + 1][k]);
    return sum;
  }
};

double cie_f(double t) {
  return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27 * t + 16) / 116;
}

}  // namespace

// Constant ρ = 0.5; all excitation (a = 0.2) in the 400–410 nm bin, all emission in 550–560 nm;
// illuminant E (S = 100). By hand: β = 0.5 everywhere but β = 0.5 + 0.2·S(405)/S(555) = 0.7 in
// the emission bin; X = 100·(0.5·∫x̄ + 0.2·∫₅₅₀⁵⁶⁰x̄)/∫ȳ over 380–780 nm, and so on.
TEST(Colorimetry, MatchesHandWorkedValuesForASyntheticMaterial) {
  ColorimetryRequest q;
  q.material = material_from_json(R"({"passive": {"reflectance": 0.5},
      "fluorescence": {"excitation": {"nm": [400, 410], "value": [0.2, 0.2]},
                       "emission": {"nm": [550, 560], "value": [1, 1]}}})");
  q.illuminants = {{"E", builtin_spectrum("E"), ""}};
  Colorimetry c = evaluate_colorimetry(q);
  ASSERT_EQ(c.grid.min_nm, 380);
  ASSERT_EQ(c.grid.bins, 40);
  const IlluminantColorimetry& r = c.illuminants.at(0);
  const int emission_bin = 17;  // 550–560 nm
  for (int i = 0; i < c.grid.bins; ++i) {
    EXPECT_NEAR(r.beta.reflected[i], 0.5, 1e-12) << i;
    EXPECT_NEAR(r.beta.fluorescent[i], i == emission_bin ? 0.2 : 0.0, 1e-12) << i;
  }

  CmfIntegrals cmf("CIE1931_2deg_xyz_cmf_360_830_1nm.csv");
  double whole[3], band[3], hand[3], white[3];
  for (int k = 0; k < 3; ++k) {
    whole[k] = cmf.integral(k + 1, 380, 780);
    band[k] = cmf.integral(k + 1, 550, 560);
  }
  for (int k = 0; k < 3; ++k) {
    hand[k] = 100 * (0.5 * whole[k] + 0.2 * band[k]) / whole[1];
    white[k] = 100 * whole[k] / whole[1];
  }
  const double fx = cie_f(hand[0] / white[0]), fy = cie_f(hand[1] / 100),
               fz = cie_f(hand[2] / white[2]);
  const double lab[3] = {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
  const double s = hand[0] + hand[1] + hand[2], sn = white[0] + white[1] + white[2];
  const double x = hand[0] / s, y = hand[1] / s, xn = white[0] / sn, yn = white[1] / sn;
  const double w = hand[1] + 800 * (xn - x) + 1700 * (yn - y);
  const double t = 1000 * (xn - x) - 650 * (yn - y);

  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.white[k], white[k], 1e-9 * white[k]) << k;
    EXPECT_NEAR(r.xyz[k], hand[k], 1e-9 * hand[k]) << k;
    EXPECT_NEAR(r.lab[k], lab[k], 1e-8) << k;
  }
  EXPECT_NEAR(r.whiteness.w, w, 1e-8);
  EXPECT_NEAR(r.whiteness.t, t, 1e-8);
  std::printf(
      "  by hand: XYZ %.6f %.6f %.6f, Lab %.6f %.6f %.6f, W %.6f, T %.6f\n"
      "  kasha:   XYZ %.6f %.6f %.6f, Lab %.6f %.6f %.6f, W %.6f, T %.6f\n",
      hand[0], hand[1], hand[2], lab[0], lab[1], lab[2], w, t, r.xyz[0], r.xyz[1], r.xyz[2],
      r.lab[0], r.lab[1], r.lab[2], r.whiteness.w, r.whiteness.t);

  // The 10° observer's tint differs in its x coefficient (900 instead of 1000).
  q.observer = Observer::cie1964_10deg;
  const IlluminantColorimetry r10 = evaluate_colorimetry(q).illuminants.at(0);
  CmfIntegrals cmf10("CIE1964_10deg_xyz_cmf_360_830_1nm.csv");
  double h10[3], w10[3];
  for (int k = 0; k < 3; ++k) {
    h10[k] = 100 * (0.5 * cmf10.integral(k + 1, 380, 780) + 0.2 * cmf10.integral(k + 1, 550, 560)) /
             cmf10.integral(2, 380, 780);
    w10[k] = 100 * cmf10.integral(k + 1, 380, 780) / cmf10.integral(2, 380, 780);
  }
  const double s10 = h10[0] + h10[1] + h10[2], sn10 = w10[0] + w10[1] + w10[2];
  const double dx = w10[0] / sn10 - h10[0] / s10, dy = w10[1] / sn10 - h10[1] / s10;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r10.xyz[k], h10[k], 1e-9 * h10[k]) << k;
  EXPECT_NEAR(r10.whiteness.w, h10[1] + 800 * dx + 1700 * dy, 1e-8);
  EXPECT_NEAR(r10.whiteness.t, 900 * dx - 650 * dy, 1e-8);
}

// Published examples: CIELAB and CIE whiteness from colour-science's documentation, and the
// 10° D65 white point of CIE 15:2004 (x₁₀, y₁₀) = (0.31382, 0.33100).
TEST(Colorimetry, PublishedLabWhitenessAndWhitePoint) {
  const double xn = 0.3127, yn = 0.3290;
  Vec3d lab = xyz_to_lab({0.20654008, 0.12197225, 0.05136952}, {xn / yn, 1.0, (1 - xn - yn) / yn});
  EXPECT_NEAR(lab[0], 41.52787529, 1e-6);
  EXPECT_NEAR(lab[1], 52.63858304, 1e-6);
  EXPECT_NEAR(lab[2], 26.92317922, 1e-6);

  // Sample xy (0.3167, 0.3334), Y = 100, illuminant xy (0.3139, 0.3311): W 93.85, T −1.305.
  auto xyz_of = [](double x, double y, double Y) -> Vec3d {
    return {x / y * Y, Y, (1 - x - y) / y * Y};
  };
  Whiteness w = cie_whiteness(xyz_of(0.3167, 0.3334, 100), xyz_of(0.3139, 0.3311, 100),
                              Observer::cie1931_2deg);
  EXPECT_NEAR(w.w, 93.85, 1e-9);
  EXPECT_NEAR(w.t, -1.305, 1e-9);
  EXPECT_TRUE(w.in_range);
  EXPECT_FALSE(
      cie_whiteness(xyz_of(0.40, 0.45, 80), xyz_of(0.3139, 0.3311, 100), Observer::cie1931_2deg)
          .in_range);

  WavelengthGrid g{380, 5, 80};
  BinnedObserver obs(g, Observer::cie1964_10deg);
  auto white = obs.xyz(g.resample(*builtin_spectrum("D65")), g.bin_nm);
  auto xy = chromaticity({white[0], white[1], white[2]});
  EXPECT_NEAR(xy[0], 0.31382, 1e-4);
  EXPECT_NEAR(xy[1], 0.33100, 1e-4);
}

// Sharma, Wu and Dalal (2005), Table 1: pairs that exercise the hue-angle wrap-around, neutral
// colours, the mean-hue rule and large differences; the formula is symmetric.
TEST(Colorimetry, Ciede2000MatchesSharmaTestData) {
  struct Pair {
    Vec3d a, b;
    double de;
  };
  const Pair pairs[] = {
      {{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
      {{50, 3.1571, -77.2803}, {50, 0, -82.7485}, 2.8615},
      {{50, 2.8361, -74.0200}, {50, 0, -82.7485}, 3.4412},
      {{50, -1.3802, -84.2814}, {50, 0, -82.7485}, 1.0000},
      {{50, 0, 0}, {50, -1, 2}, 2.3669},
      {{50, 2.49, -0.001}, {50, -2.49, 0.0009}, 7.1792},
      {{50, 2.49, -0.001}, {50, -2.49, 0.0011}, 7.2195},
      {{50, -0.001, 2.49}, {50, 0.0009, -2.49}, 4.8045},
      {{50, 2.5, 0}, {50, 0, -2.5}, 4.3065},
      {{50, 2.5, 0}, {73, 25, -18}, 27.1492},
      {{50, 2.5, 0}, {61, -5, 29}, 22.8977},
      {{50, 2.5, 0}, {56, -27, -3}, 31.9030},
      {{50, 2.5, 0}, {58, 24, 15}, 19.4535},
      {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
      {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
      {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
      {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
      {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
  };
  for (const Pair& p : pairs) {
    EXPECT_NEAR(ciede2000(p.a, p.b), p.de, 5e-5) << p.a[1] << " " << p.b[1];
    EXPECT_NEAR(ciede2000(p.b, p.a), p.de, 5e-5) << p.a[1] << " " << p.b[1];
  }
  EXPECT_EQ(ciede2000({52, 10, -30}, {52, 10, -30}), 0.0);
}

// `kasha delta-e` accepts L* in [0, 1e4] and a*, b* in [-1e4, 1e4]: at every corner of that box,
// and at the neutral axis where the hue is undefined, the difference is a finite number.
TEST(Colorimetry, Ciede2000IsFiniteOverTheAcceptedRange) {
  std::vector<Vec3d> corners;
  for (double L : {0.0, 1e4})
    for (double a : {-1e4, 0.0, 1e4})
      for (double b : {-1e4, 0.0, 1e4}) corners.push_back({L, a, b});
  for (const Vec3d& p : corners)
    for (const Vec3d& q : corners)
      EXPECT_TRUE(std::isfinite(ciede2000(p, q)))
          << p[0] << "," << p[1] << "," << p[2] << " " << q[0] << "," << q[1] << "," << q[2];
}

// Under the lamp it was taken under, an unclipped "as is" material is the sample (ΔE00 = 0);
// under another lamp the fluorescence it froze in shows. Clipping is reported, and the material
// file written for it resamples to the same reflectance.
TEST(Colorimetry, AsIsMaterialMatchesUnderItsOwnLampOnly) {
  ColorimetryRequest q;
  q.material = material_from_json(R"({"passive": {"reflectance": 0.6},
      "fluorescence": {"excitation": {"gaussian_nm": 360, "fwhm_nm": 40, "scale": 0.3},
                       "emission": {"gaussian_nm": 440, "fwhm_nm": 40}}})");
  q.illuminants = {{"D65", builtin_spectrum("D65"), ""}, {"A", builtin_spectrum("A"), ""}};
  q.as_is_lamp = NamedSpectrum{"D65", builtin_spectrum("D65"), ""};
  Colorimetry c = evaluate_colorimetry(q);
  ASSERT_TRUE(c.as_is);
  EXPECT_TRUE(c.as_is->clipped_nm.empty());
  EXPECT_LT(c.illuminants[0].as_is->delta_e00, 1e-9);
  EXPECT_GT(c.illuminants[1].as_is->delta_e00, 0.5);  // less UV under A: the paper is yellower
  EXPECT_GT(c.illuminants[0].whiteness.w, c.illuminants[1].whiteness.w);

  std::string file = (scratch_dir() / "as_is.json").string();
  write_as_is_material(file, *c.as_is, "test");
  Material reloaded = discretize_material(load_material_file(file, ""), c.grid);
  for (int i = 0; i < c.grid.bins; ++i)
    EXPECT_NEAR(reloaded.rho[i], c.as_is->reflectance[i], 2e-4) << c.grid.center(i);

  // A brightened paper, dark in the UV and bright in the visible: its fluorescence pushes β above
  // 1 around the emission peak, where the as-is reflectance is clipped, and says so.
  q.material = material_from_json(R"({"passive": {"reflectance":
        {"nm": [380, 400, 410, 780], "value": [0.1, 0.1, 0.85, 0.85]}},
      "fluorescence": {"excitation": {"gaussian_nm": 360, "fwhm_nm": 40, "scale": 0.8},
                       "emission": {"gaussian_nm": 440, "fwhm_nm": 40}}})");
  Colorimetry hot = evaluate_colorimetry(q);
  ASSERT_FALSE(hot.as_is->clipped_nm.empty());
  for (double nm : hot.as_is->clipped_nm) {
    EXPECT_GT(nm, 400);
    EXPECT_LT(nm, 480);
  }
  EXPECT_GT(hot.illuminants[0].as_is->delta_e00, 0.1);
}

TEST(Colorimetry, CommandWritesJsonCsvAndPlot) {
  const std::string material = source_path("scenes/materials/postit.json");
  const std::string d = scratch_dir().string();
  auto r = run_kasha("colorimetry '" + material + "' --illuminant D65 --json " + d +
                     "/one.json --observer 10");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json one = nlohmann::json::parse(std::ifstream(d + "/one.json"));
  for (const char* key : {"XYZ", "Lab", "whiteness", "tint", "beta"})
    EXPECT_TRUE(one.contains(key));
  EXPECT_EQ(one["observer_deg"], 10);
  EXPECT_EQ(one["beta"]["nm"].size(), one["beta"]["value"].size());

  r = run_kasha("colorimetry '" + material + "' --illuminant D65 --illuminant A --illuminant '" +
                source_path("scenes/data/RIT_Pointer_Philips_TL-84.csv") + "' --as-is D65 --json " +
                d + "/many.json --csv " + d + "/many.csv --plot " + d + "/many.png --write-as-is " +
                d + "/as_is.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json many = nlohmann::json::parse(std::ifstream(d + "/many.json"));
  ASSERT_EQ(many["illuminants"].size(), 3u);
  EXPECT_FALSE(many.contains("XYZ"));
  EXPECT_TRUE(many["illuminants"][1].contains("as_is"));
  // The Post-it's β exceeds 1 under D65 around its emission peak (≈ 520 nm).
  EXPECT_FALSE(many["as_is_material"]["clipped_nm"].empty());
  EXPECT_TRUE(std::filesystem::exists(d + "/many.png"));
  std::ifstream csv(d + "/many.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 4);  // header + a row per illuminant
  EXPECT_NE(r.out.find("ΔE00 as is"), std::string::npos) << r.out;
  // The written "as is" material gives colorimetry's as-is colour back.
  r = run_kasha("colorimetry " + d + "/as_is.json --illuminant A --json " + d + "/back.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json back = nlohmann::json::parse(std::ifstream(d + "/back.json"));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(back["Lab"][k].get<double>(),
                many["illuminants"][1]["as_is"]["Lab"][k].get<double>(), 0.01);
}

TEST(Colorimetry, BadInputsGiveOneLineAndNoOutput) {
  const std::string material = source_path("scenes/materials/postit.json");
  const std::string out = (scratch_dir() / "out.json").string();
  auto expect_error = [&](const std::string& args, const std::string& expected) {
    auto r = run_kasha("colorimetry " + args + " --json " + out);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.err.find("kasha: error: " + expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  };
  expect_error("'" + material + "' --illuminant D66", "--illuminant D66: not a built-in spectrum");
  expect_error("'" + material + "' --illuminant '{\"line_nm\": 250}'",
               "--illuminant {\"line_nm\": 250}: the illuminant has no light the observer sees");
  // A line at 700 nm: the observer's z̄ is 0 there, so the white's Z is 0 and CIELAB (Z / Zn) is
  // undefined; it used to print b* -inf (null in the JSON).
  expect_error("'" + material + "' --illuminant '{\"line_nm\": 700}'",
               "--illuminant {\"line_nm\": 700}: the perfect white's Z is 0");
  // A lamp the observer cannot see makes no "as is" material either, as it makes no row.
  const std::string zero = write_file("zero.csv", "wavelength_nm,relative_spd\n300,0\n800,0\n");
  expect_error("'" + material + "' --as-is '" + zero + "'",
               "--as-is " + zero + ": the illuminant has no light the observer sees");
  expect_error("'" + material + "' --illuminant '{\"gaussian_nm\": 500}'",
               "--illuminant {\"gaussian_nm\": 500}: /: missing required key \"fwhm_nm\"");
  expect_error("'" + material + "' --write-as-is " + out + ".x", "--write-as-is: needs --as-is");
  expect_error("/nonexistent.json", "/nonexistent.json: cannot open file");
  auto r = run_kasha("colorimetry '" + material + "' --csv '" + material + "'");
  EXPECT_NE(r.err.find(": is the material file "), std::string::npos) << r.err;
  r = run_kasha("colorimetry '" + material + "' --json " + scratch_dir().string());
  EXPECT_NE(r.err.find(": is a directory"), std::string::npos) << r.err;
}

TEST(Colorimetry, JsonOnTheCommandLineResolvesCsvPathsAgainstTheWorkingDirectory) {
  // The folder used to be taken from the option's text: {"csv": "data/A.csv"} looked for
  // data/data/A.csv and {"csv": "./A.csv"} failed.
  const std::string d = scratch_dir().string();
  write_file("data/lamp.csv", "400,1\n500,2\n600,3\n700,2\n");
  const std::string material = source_path("scenes/materials/postit.json");
  auto r = run_kasha_env("-C '" + d + "'",
                         "colorimetry '" + material +
                             "' --illuminant data/lamp.csv --illuminant '{\"csv\": "
                             "\"data/lamp.csv\"}' --illuminant '{\"csv\": \"./data/lamp.csv\"}' "
                             "--json out.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(d + "/out.json"));
  ASSERT_EQ(j["illuminants"].size(), 3u);
  for (int i = 1; i < 3; ++i) EXPECT_EQ(j["illuminants"][i]["XYZ"], j["illuminants"][0]["XYZ"]);
  // A JSON value longer than a file name may be is still a JSON value (it used to fail in
  // std::filesystem with "File name too long").
  std::string nm, value;
  for (int w = 400; w <= 700; w += 2) {
    nm += (nm.empty() ? "" : ", ") + std::to_string(w);
    value += (value.empty() ? "" : ", ") + std::string("1");
  }
  r = run_kasha("colorimetry '" + material + "' --illuminant '{\"nm\": [" + nm + "], \"value\": [" +
                value + "]}'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(Colorimetry, ControlBytesInNamesAreEscapedInTheTable) {
  // A material name or an illuminant file name holding terminal controls used to reach stdout raw.
  const std::string material = write_file(
      "m.json",
      R"({"kasha_material": 1, "name": "\u001b[31mred\u0007", "passive": {"reflectance": 0.5}})");
  const std::string lamp = write_file("x\x1b[2Jname.csv", "400,1\n700,1\n");
  auto r = run_kasha("colorimetry '" + material + "' --illuminant '" + lamp + "' --as-is '" + lamp +
                     "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x07'), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\x1B[31mred\\x07"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("x\\x1B[2Jname.csv"), std::string::npos) << r.out;
}

TEST(Colorimetry, NamesThatAreNotUtf8GoIntoTheAsIsMaterialEscaped) {
  // The material path and the lamp's label reach the JSON of --write-as-is; JSON needs UTF-8 and
  // nlohmann used to fail there (type_error.316).
  const std::string material = write_file(
      "m\xff.json", R"({"kasha_material": 1, "name": "w", "passive": {"reflectance": 0.5}})");
  const std::string lamp = write_file("l\xfe.csv", "400,1\n700,2\n");
  const std::string d = scratch_dir().string();
  auto r = run_kasha("colorimetry '" + material + "' --as-is '" + lamp + "' --write-as-is " + d +
                     "/as_is.json --json " + d + "/c.json --csv " + d + "/c.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json as_is = nlohmann::json::parse(std::ifstream(d + "/as_is.json"));
  EXPECT_NE(as_is["diagnostics"]["source"].get<std::string>().find("m\\xFF.json"),
            std::string::npos);
  EXPECT_NE(as_is["diagnostics"]["lamp"].get<std::string>().find("l\\xFE.csv"), std::string::npos);
  EXPECT_NE(as_is["name"].get<std::string>().find("l\\xFE.csv"), std::string::npos);
  nlohmann::json c = nlohmann::json::parse(std::ifstream(d + "/c.json"));
  EXPECT_NE(c["as_is_material"]["lamp"].get<std::string>().find("l\\xFE.csv"), std::string::npos);
  // The written material reads back.
  r = run_kasha("colorimetry " + d + "/as_is.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// The plotter's own last error line is the message (not a path to a log already deleted), and
// TMPDIR plays no part in a plot.
TEST(Colorimetry, PlotErrorsSayWhatThePlotterSaidAndTmpdirPlaysNoPart) {
  const std::string material = source_path("scenes/materials/postit.json");
  const std::filesystem::path d = scratch_dir() / "plot";
  std::filesystem::create_directories(d);
  const std::string txt = (d / "o.txt").string(), png = (d / "o.png").string();
  auto r = run_kasha("colorimetry '" + material + "' --plot '" + txt + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("kasha: error: --plot " + txt + ": plotting failed: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("Format 'txt' is not supported"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(d));

  r = run_kasha_env("TMPDIR=" + (d / "missing").string(),
                    "colorimetry '" + material + "' --plot '" + png + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(png));
}

namespace {

// A flat 1 × 1 sample facing up at the centre of an inward sphere (r = 0.8) that emits `lamp`
// uniformly and is black: the sample sees a uniform hemisphere and nothing it sends out comes back,
// so its radiance is β∘L exactly. The camera looks straight down from inside the sphere and sees
// only the sample.
std::string hemisphere_scene(const std::string& material_file, const std::string& lamp) {
  return write_file("hemisphere.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0.7, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_deg": 60,
               "width": 16, "height": 16},
    "materials": {"sample": {"file": ")" + material_file +
                                           R"("}, "black": {}},
    "shapes": [
      {"type": "quad", "corner": [-0.5, 0, -0.5], "u": [0, 0, 1], "v": [1, 0, 0], "material": "sample"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.8, "inward": true, "material": "black",
       "emission": )" + lamp + R"(}]})");
}

}  // namespace

class Hemisphere : public ::testing::TestWithParam<std::string> {};

TEST_P(Hemisphere, RenderShowsColorimetryXyz) {
  const std::string integrator = GetParam();
  const std::string material = source_path("scenes/materials/postit.json");
  const std::string scene =
      hemisphere_scene(material, R"({"csv": ")" + source_path("scenes/data/CIE_D65_300_780.csv") +
                                     R"(", "scale": 0.01})");
  RenderSettings s;
  s.integrator = integrator;
  s.spectral = false;
  s.passes = 12;
  s.integrator_settings.spp = 64;
  s.integrator_settings.photons = 1 << 18;
  RenderResult r = render_scene(scene, s);

  ColorimetryRequest q;
  q.material = load_material_file(material, "");
  q.illuminants = {{"lamp", r.scene.emitters.at(0).radiance, ""}};
  Colorimetry c = evaluate_colorimetry(q);
  ASSERT_EQ(c.grid.min_nm, r.scene.grid.min_nm);
  ASSERT_EQ(c.grid.bins, r.scene.grid.bins);
  // Colorimetry's XYZ is relative to a perfect white at Y = 100; the film's is absolute.
  const double white_y = BinnedObserver(c.grid).xyz(c.illuminants[0].lamp, c.grid.bin_nm)[1];
  BinStats px = pixel_statistics(r.image, false);
  for (int k = 0; k < 3; ++k) {
    const double expected = c.illuminants[0].xyz[k] * white_y / 100;
    const double tolerance = 4 * px.standard_error[k] + 1e-3 * expected;
    EXPECT_NEAR(px.mean[k], expected, tolerance) << integrator << " row " << k;
    EXPECT_LT(px.standard_error[k], 0.01 * expected) << integrator << " row " << k;
    std::printf("  %s %c: image %.5f ± %.5f, colorimetry %.5f (%+.3f %%)\n", integrator.c_str(),
                "XYZ"[k], px.mean[k] * 100 / white_y, px.standard_error[k] * 100 / white_y,
                c.illuminants[0].xyz[k], 100 * (px.mean[k] / expected - 1));
  }
  EXPECT_EQ(r.rejected, 0);
}

INSTANTIATE_TEST_SUITE_P(Colorimetry, Hemisphere,
                         ::testing::ValuesIn(IntegratorRegistry::names(true)),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });
