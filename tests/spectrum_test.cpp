// Spectra: every form keeps its integral on the grid; CIE tables; errors name their source.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "color/cie_observer.h"
#include "color/color_space.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/spectrum_parser.h"
#include "spectrum/wavelength_grid.h"
#include "test_support.h"

using namespace kasha;
using kasha::test::error_of;

namespace {

WavelengthGrid grid(double lo, double hi, double bin) {
  WavelengthGrid g;
  g.min_nm = lo;
  g.bin_nm = bin;
  g.bins = static_cast<int>(std::lround((hi - lo) / bin));
  return g;
}

SpectrumPtr parse(const std::string& json) {
  return parse_spectrum(JsonNode::from_json(nlohmann::json::parse(json), "test.json"));
}

double grid_integral(const WavelengthGrid& g, const Spectrum& s) {
  double sum = 0;
  for (double v : g.resample(s)) sum += v * g.bin_nm;
  return sum;
}

std::array<double, 2> d65_xy(const WavelengthGrid& g) {
  BinnedObserver obs(g);
  auto xyz = obs.xyz(g.resample(*builtin_spectrum("D65")), g.bin_nm);
  return chromaticity({xyz[0], xyz[1], xyz[2]});
}

}  // namespace

TEST(Colour, D65WhitePointThroughTheCieTables) {
  // At the resolution of the D65 table and finer the published xy holds to 1e-4.
  for (double bin : {1.0, 5.0}) {
    auto xy = d65_xy(grid(380, 780, bin));
    EXPECT_NEAR(xy[0], 0.3127, 1e-4) << bin;
    EXPECT_NEAR(xy[1], 0.3290, 1e-4) << bin;
  }
  // 10 nm bin averages of the CMFs and of D65 shift it by about 1e-4: measured, not hidden.
  auto xy = d65_xy(grid(380, 780, 10));
  EXPECT_NEAR(xy[0], 0.3127, 2e-4);
  EXPECT_NEAR(xy[1], 0.3290, 2e-4);
}

TEST(Colour, D65IsWhiteInLinearSrgb) {
  WavelengthGrid g = grid(380, 780, 5);
  BinnedObserver obs(g);
  auto xyz = obs.xyz(g.resample(*builtin_spectrum("D65")), g.bin_nm);
  Vec3d rgb = xyz_to_linear_srgb({xyz[0], xyz[1], xyz[2]});
  EXPECT_NEAR(rgb[0] / rgb[1], 1.0, 2e-3);
  EXPECT_NEAR(rgb[2] / rgb[1], 1.0, 2e-3);
  // Y of D65 (relative, 100 at 560 nm) is 100 · Σȳ·Δλ-weighted ≈ 10567 with no 683 factor.
  EXPECT_NEAR(xyz[1] / 10567.0, 1.0, 5e-3);
}

TEST(Spectrum, LineKeepsItsIntegralInOneBin) {
  WavelengthGrid g = grid(380, 780, 10);
  auto s = parse(R"({"line_nm": 405, "scale": 3})");
  auto v = g.resample(*s);
  for (int i = 0; i < g.bins; ++i)
    EXPECT_DOUBLE_EQ(v[i], i == 2 ? 0.3 : 0.0) << i;  // [400, 410) holds 405
  EXPECT_NEAR(grid_integral(g, *s), 3.0, 1e-12);
  // On a bin edge it belongs to the upper bin; at the top edge, to the last bin.
  auto edge = g.resample(*parse(R"({"line_nm": 410})"));
  EXPECT_DOUBLE_EQ(edge[3], 0.1);
  auto top = g.resample(*parse(R"({"line_nm": 780})"));
  EXPECT_DOUBLE_EQ(top[g.bins - 1], 0.1);
}

TEST(Spectrum, SubBinGaussianKeepsItsIntegral) {
  WavelengthGrid g = grid(380, 780, 10);
  for (double fwhm : {0.5, 2.0, 7.0, 40.0}) {
    auto s = parse(R"({"gaussian_nm": 503.7, "fwhm_nm": )" + std::to_string(fwhm) + "}");
    double sigma = fwhm / (2 * std::sqrt(2 * std::log(2.0)));
    EXPECT_NEAR(grid_integral(g, *s), sigma * std::sqrt(2 * M_PI), 1e-9 * sigma) << fwhm;
  }
  // A 0.5 nm gaussian lies inside its bin: nearly all of it in [500, 510).
  auto v = g.resample(*parse(R"({"gaussian_nm": 505, "fwhm_nm": 0.5})"));
  EXPECT_GT(v[12] * 10, 0.999 * 0.5 / (2 * std::sqrt(2 * std::log(2.0))) * std::sqrt(2 * M_PI));
}

TEST(Spectrum, TabulatedIsAveragedExactlyNotPointSampled) {
  WavelengthGrid g = grid(400, 500, 10);
  // A triangle 400→450→500 with peak 2 integrates to 100; a 1 nm spike between samples too.
  auto tri = parse(R"({"nm": [400, 450, 500], "value": [0, 2, 0]})");
  EXPECT_NEAR(grid_integral(g, *tri), 100.0, 1e-12);
  EXPECT_NEAR(g.resample(*tri)[0], 0.2, 1e-12);  // (0 + 0.4)/2 over [400, 410]
  auto spike = parse(R"({"nm": [452, 452.5, 453], "value": [0, 10, 0]})");
  EXPECT_NEAR(grid_integral(g, *spike), 5.0, 1e-12);
  EXPECT_NEAR(g.resample(*spike)[5], 0.5, 1e-12);
  // Zero outside the tabulated range.
  auto part = parse(R"({"nm": [405, 415], "value": [1, 1]})");
  EXPECT_NEAR(grid_integral(g, *part), 10.0, 1e-12);
}

TEST(Spectrum, ConstantAndBuiltins) {
  WavelengthGrid g = grid(380, 780, 10);
  EXPECT_NEAR(grid_integral(g, *parse("0.25")), 100.0, 1e-9);
  EXPECT_NEAR(grid_integral(g, *parse(R"("E")")), 40000.0, 1e-6);
  auto d65 = g.resample(*parse(R"("D65")"));
  EXPECT_NEAR(d65[18], 100.0, 3.0);  // the bin around 560 nm
  for (const char* name : {"\"A\"", "\"F11\"", "\"D50\"", "\"F2\"", "\"F7\""})
    EXPECT_GT(grid_integral(g, *parse(name)), 0);
}

TEST(Spectrum, BlackbodyIsPlanckPerNanometre) {
  // ∫ B dλ over all wavelengths = σ T⁴ / π.
  WavelengthGrid wide = grid(50, 200050, 100);
  double T = 3000, sigma = 5.670374419e-8;
  EXPECT_NEAR(
      grid_integral(wide, *parse(R"({"blackbody_K": 3000})")) / (sigma * std::pow(T, 4) / M_PI),
      1.0, 1e-4);
  // Wien's peak near 2898/T µm; a scale multiplies.
  WavelengthGrid g = grid(380, 780, 1);
  auto v = g.resample(*parse(R"({"blackbody_K": 5000, "scale": 2})"));
  auto peak = std::max_element(v.begin(), v.end()) - v.begin();
  EXPECT_NEAR(g.center(static_cast<int>(peak)), 579.5, 1.0);
}

TEST(Spectrum, CsvColumnsCommentsAndHeader) {
  std::string path =
      test::write_file("s.csv", "# comment\nnm,low,high\n400,0.1,0.5\n500,0.3,0.7\n");
  WavelengthGrid g = grid(400, 500, 100);
  auto s = parse(R"({"csv": ")" + path + R"(", "column": "high"})");
  EXPECT_NEAR(g.resample(*s)[0], 0.6, 1e-12);
  EXPECT_NE(
      error_of([&] { parse(R"({"csv": ")" + path + R"("})"); }).find("choose one with \"column\""),
      std::string::npos);
  EXPECT_NE(error_of([&] {
              parse(R"({"csv": ")" + path + R"(", "column": "mid"})");
            }).find("no column named"),
            std::string::npos);
}

TEST(Spectrum, BadSpectraGiveOneClearLine) {
  auto check = [](const std::string& json, const std::string& expected) {
    std::string msg = error_of([&] { parse(json); });
    EXPECT_NE(msg.find(expected), std::string::npos) << json << " -> " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  check(R"({"nm": [400, 390], "value": [1, 1]})", "wavelengths must increase");
  check(R"({"nm": [400, 500], "value": [1, -0.5]})", "negative value -0.5");
  check(R"({"nm": [400, 500], "value": [1]})", "2 wavelengths but 1 values");
  check(R"({"nm": [400, 500], "value": [1, "x"]})",
        "test.json: /value/1: expected a number, got a string");
  check(R"(-1)", "negative spectrum value");
  check(R"("D66")", "unknown built-in spectrum \"D66\"");
  check(R"({"line_nm": 405, "colour": 1})", "test.json: /colour: unknown key");
  check(R"({"gaussian_nm": 450})", "missing required key \"fwhm_nm\"");
  check(R"({"csv": "/nonexistent/x.csv"})", "/nonexistent/x.csv: cannot open file");
  check(R"([1, 2])", "expected a spectrum");

  std::string nan = test::write_file("nan.csv", "400,1\n500,nan\n");
  check(R"({"csv": ")" + nan + R"("})", "nan.csv: line 2, column 2: value is not finite");
  std::string text = test::write_file("text.csv", "nm,v\n400,1\n500,abc\n");
  check(R"({"csv": ")" + text + R"("})", "text.csv: line 3, column 2: not a number: \"abc\"");
  std::string unsorted = test::write_file("unsorted.csv", "500,1\n400,1\n");
  check(R"({"csv": ")" + unsorted + R"("})",
        "unsorted.csv: line 2: at 400 nm: wavelengths must increase");
}

TEST(Spectrum, ValuesBeyondFloatRangeNameTheirPlaceAndValue) {
  // Float kernels carry spectra: any value above 1e30, raw or scaled, is refused where it is.
  auto check = [](const std::string& json, const std::string& expected) {
    std::string msg = error_of([&] { parse(json); });
    EXPECT_NE(msg.find(expected), std::string::npos) << json << " -> " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  check("1e40", "test.json: /: a spectrum value of 1e+40 is beyond 1e30");
  check(R"({"nm": [400, 500], "value": [1, 2e31]})",
        "test.json: /: at 500 nm: a spectrum value of 2e+31 is beyond 1e30");
  check(R"({"nm": [400, 500], "value": [1, 1e20], "scale": 1e20})",
        "test.json: /scale: a spectrum value of 1e+40 is beyond 1e30");
  check(R"({"nm": [400, 500], "value": [1, 1e30], "scale": 1e300})",
        "test.json: /scale: a spectrum value of inf is beyond 1e30");
  check(R"({"gaussian_nm": 450, "fwhm_nm": 20, "scale": 1e40})",
        "test.json: /scale: a spectrum value of 1e+40 is beyond 1e30");
  check(R"({"line_nm": 405, "scale": 3e30})",
        "test.json: /scale: a spectrum value of 3e+30 is beyond 1e30");
  // A 6500 K blackbody peaks at 4.75e4 per nm (Wien, Planck): scaled by 1e27 it passes the limit.
  const double planck_peak = parse(R"({"blackbody_K": 6500})")->peak();
  EXPECT_NEAR(planck_peak, 4.7522e4, 1.0);
  std::ostringstream scaled;
  scaled << "test.json: /scale: a spectrum value of " << planck_peak * 1e27 << " is beyond 1e30";
  check(R"({"blackbody_K": 6500, "scale": 1e27})", scaled.str());
  // CSV cells name the file and line.
  std::string big = test::write_file("big.csv", "# nm, value\n400,1\n500,1e300\n");
  check(R"({"csv": ")" + big + R"("})",
        "big.csv: line 3: at 500 nm: a spectrum value of 1e+300 is beyond 1e30");
  check(R"({"csv": ")" + big + R"(", "scale": 0})",
        "big.csv: line 3: at 500 nm: a spectrum value of 1e+300");
  std::string huge = test::write_file("huge.csv", "400,1\n500,1e400\n");
  check(R"({"csv": ")" + huge + R"("})", "huge.csv: line 2, column 2: value is not finite");
  // Wavelengths are finite and positive.
  check(R"({"nm": [0, 500], "value": [1, 1]})",
        "test.json: /: at 0 nm: wavelength must be positive");
  std::string zero = test::write_file("zero.csv", "-5,1\n500,1\n");
  check(R"({"csv": ")" + zero + R"("})", "zero.csv: line 1: at -5 nm: wavelength must be positive");
  // The limit itself is a value.
  EXPECT_DOUBLE_EQ(parse("1e30")->peak(), 1e30);
  EXPECT_DOUBLE_EQ(parse(R"({"gaussian_nm": 450, "fwhm_nm": 20, "scale": 1e30})")->peak(), 1e30);
}

TEST(WavelengthGrid, AutomaticRangeAddsUvOnlyWhenUvExcites) {
  GridRequest req;
  auto uv_lamp = parse(R"({"line_nm": 365})")->support();
  auto visible_lamp = parse(R"("F11")")->support();
  auto brightener = parse(R"({"nm": [300, 340, 400, 420], "value": [0, 0.6, 0.4, 0]})")->support();
  // No fluorescence: the visible range only.
  WavelengthGrid g = choose_grid(req, {uv_lamp}, {});
  EXPECT_EQ(g.min_nm, 380);
  EXPECT_EQ(g.max_nm(), 780);
  EXPECT_EQ(g.bins, 40);
  // A visible lamp on a UV-excited material: nothing to extend.
  EXPECT_EQ(choose_grid(req, {visible_lamp}, {brightener}).min_nm, 380);
  // A 365 nm line on it: down to the bin holding 365, on edges aligned with 380.
  g = choose_grid(req, {uv_lamp}, {brightener});
  EXPECT_EQ(g.min_nm, 360);
  EXPECT_EQ(g.bins, 42);
  EXPECT_EQ(g.bin_of(365), 0);
  // A fixed range is kept as given.
  req.min_nm = 300;
  req.bin_nm = 5;
  g = choose_grid(req, {}, {});
  EXPECT_EQ(g.min_nm, 300);
  EXPECT_EQ(g.bins, 96);
}
