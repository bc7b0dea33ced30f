#pragma once
// RGB colours as spectra, the way pbrt-v4 turns them into spectra: a linear sRGB colour becomes
// the smooth spectrum S(c0 λ² + c1 λ + c2) (S the sigmoid, inside (0, 1)) whose colour under D65
// is that RGB colour, its coefficients interpolated in a table fitted at build time (Jakob &
// Hanika 2019; spectrum/rgb_spectrum_fit.h). Reflectance RGB must lie in [0, 1]; an illuminant
// RGB (any size) is scale · S(λ) · D65(λ) with D65 normalised to luminance 1 (pbrt-v4's
// RGBIlluminantSpectrum), so it has the RGB's colour and its Y.
#include <array>

#include "spectrum/rgb_spectrum_fit.h"
#include "spectrum/spectrum.h"

namespace kasha {

// The coefficients of the reflectance whose colour is rgb (each in [0, 1]; clamped).
SigmoidCoefficients rgb_sigmoid(const std::array<double, 3>& rgb);

// An RGB colour of any size as scale · S(c): the sigmoid of rgb / scale, scale = 2·max (pbrt-v4's
// RGBUnboundedSpectrum).
SigmoidCoefficients rgb_unbounded_sigmoid(const std::array<double, 3>& rgb, double* scale);

// D65 over its luminance, ∫ D65 ȳ dλ / ∫ ȳ dλ = 1, at nm (0 outside 300–780 nm).
double d65_normalized(double nm);
// The same as a spectrum (piecewise linear through the table's 5 nm samples).
SpectrumPtr d65_luminance_one();

class RgbReflectanceSpectrum : public Spectrum {
 public:
  explicit RgbReflectanceSpectrum(const std::array<double, 3>& rgb) : c_(rgb_sigmoid(rgb)) {}
  SpectralSupport support() const override { return {false, true, 0, 0}; }

 protected:
  double raw_integral(double a, double b) const override;
  double raw_value(double nm) const override { return sigmoid_spectrum(c_, nm); }
  double raw_peak() const override { return 1.0; }

 private:
  SigmoidCoefficients c_;
};

class RgbIlluminantSpectrum : public Spectrum {
 public:
  explicit RgbIlluminantSpectrum(const std::array<double, 3>& rgb);
  SpectralSupport support() const override { return {false, false, 300, 780}; }

 protected:
  double raw_integral(double a, double b) const override;
  double raw_value(double nm) const override;
  double raw_peak() const override;

 private:
  SigmoidCoefficients c_;
  double scale_ = 0;
};

}  // namespace kasha
