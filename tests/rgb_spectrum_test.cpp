// RGB → spectrum (spectrum/rgb_spectrum.h) against colorimetry computed here: every 8-bit sRGB
// colour (a lattice of every third code value in each channel, corners and greys included) turned
// into a reflectance spectrum has, under D65 with the CIE 1931 observer on a 1 nm grid, the colour
// of the sRGB value within ΔE2000 0.5, and the spectrum stays inside [0, 1]; an illuminant RGB
// has the RGB's XYZ (luminance included) within 1 %.
#include "spectrum/rgb_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>

#include "color/cie_observer.h"
#include "color/color_space.h"
#include "colorimetry/cie_lab.h"
#include "colorimetry/ciede2000.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/spectrum_parser.h"
#include "test_support.h"

using namespace kasha;

namespace {

double decode(int code) {
  double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// XYZ of the spectrum s (or of the illuminant alone when s is null) lit by D65, relative to D65's
// Y, on a 1 nm grid from 360 to 780 nm (the tables sampled once: 636 056 colours go through it).
struct Colorimeter {
  std::vector<double> nm, lit[3], unlit[3];
  double lit_norm = 0, unlit_norm = 0;
  Colorimeter() {
    const std::array<SpectrumPtr, 3>& cmf = cie_cmf(Observer::cie1931_2deg);
    SpectrumPtr d65 = builtin_spectrum("D65");
    for (double l = 360; l <= 780; l += 1) {
      double w = (l == 360 || l == 780) ? 0.5 : 1.0;
      nm.push_back(l);
      for (int k = 0; k < 3; ++k) {
        lit[k].push_back(w * d65->value(l) * cmf[k]->value(l));
        unlit[k].push_back(w * cmf[k]->value(l));
      }
      lit_norm += lit[1].back();
      unlit_norm += unlit[1].back();
    }
  }
  Vec3d xyz(const std::function<double(double)>& s, bool with_d65) const {
    Vec3d out{0, 0, 0};
    for (size_t i = 0; i < nm.size(); ++i) {
      double v = s(nm[i]);
      for (int k = 0; k < 3; ++k) out[k] += v * (with_d65 ? lit : unlit)[k][i];
    }
    for (double& v : out) v /= with_d65 ? lit_norm : unlit_norm;
    return out;
  }
};

TEST(RgbSpectrum, EverySrgbColourRoundTripsWithinHalfADeltaE) {
  Colorimeter meter;
  const Vec3d white = linear_srgb_to_xyz({1, 1, 1});
  double worst = 0, lowest = 1, highest = 0;
  Vec3d worst_rgb{};
  int count = 0;
  std::vector<int> codes;
  for (int c = 0; c <= 255; c += 3) codes.push_back(c);  // 0, 3, …, 255
  for (int r : codes)
    for (int g : codes)
      for (int b : codes) {
        const std::array<double, 3> rgb = {decode(r), decode(g), decode(b)};
        const SigmoidCoefficients c = rgb_sigmoid(rgb);
        double lo = 1, hi = 0;
        const Vec3d xyz = meter.xyz(
            [&](double nm) {
              double v = sigmoid_spectrum(c, nm);
              lo = std::min(lo, v), hi = std::max(hi, v);
              return v;
            },
            true);
        lowest = std::min(lowest, lo), highest = std::max(highest, hi);
        const double de =
            ciede2000(xyz_to_lab(xyz, white),
                      xyz_to_lab(linear_srgb_to_xyz({rgb[0], rgb[1], rgb[2]}), white));
        if (de > worst) worst = de, worst_rgb = {double(r), double(g), double(b)};
        ++count;
      }
  std::printf("%d colours: worst ΔE2000 %.3f at sRGB (%g, %g, %g); spectra within [%g, %g]\n",
              count, worst, worst_rgb[0], worst_rgb[1], worst_rgb[2], lowest, highest);
  EXPECT_LE(worst, 0.5);
  EXPECT_GE(lowest, 0.0);
  EXPECT_LE(highest, 1.0);
}

TEST(RgbSpectrum, AnIlluminantRgbHasTheRgbsXyz) {
  Colorimeter meter;
  for (std::array<double, 3> rgb : {std::array<double, 3>{1, 1, 1},
                                    {0.2, 0.5, 0.9},
                                    {3, 0.1, 0.4},
                                    {0.05, 0.05, 0.02},
                                    {12, 8, 1}}) {
    RgbIlluminantSpectrum s(rgb);
    const Vec3d got = meter.xyz([&](double nm) { return s.value(nm); }, false);
    const Vec3d want = linear_srgb_to_xyz({rgb[0], rgb[1], rgb[2]});
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got[k], want[k], 0.01 * std::max(want[k], want[1]))
          << "rgb (" << rgb[0] << ", " << rgb[1] << ", " << rgb[2] << ") component " << k;
  }
}

TEST(RgbSpectrum, SceneSpectraTakeRgbAndRejectItOutOfRange) {
  auto parse = [](const std::string& text) {
    return parse_spectrum(JsonNode::parse_text(text, "test", ""));
  };
  // A reflectance's bin averages stay in [0, 1]; the grey one is flat.
  SpectrumPtr grey = parse(R"({"rgb": [0.3, 0.3, 0.3]})");
  EXPECT_NEAR(grey->integral(500, 510) / 10, 0.3, 1e-9);
  EXPECT_NE(test::error_of([&] { parse(R"({"rgb": [0.3, 1.2, 0.3]})"); }).find("outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { parse(R"({"rgb": [0.3, 0.3]})"); }).find("three numbers"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { parse(R"({"rgb_illuminant": [-1, 0, 0]})"); }).find("outside"),
            std::string::npos);
  SpectrumPtr sky = parse(R"({"rgb_illuminant": [0.4, 0.6, 1.0], "scale": 2})");
  EXPECT_GT(sky->integral(450, 460), sky->integral(650, 660));
}

}  // namespace
