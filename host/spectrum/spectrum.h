#pragma once
// Continuous spectral functions of wavelength (nm). Rendering never point-samples them: the
// wavelength grid takes their exact average over each bin through integral().
#include <memory>
#include <string>
#include <vector>

namespace kasha {

// Where a spectrum can be non-zero. Unbounded spectra (constants) never drive the automatic range.
struct SpectralSupport {
  bool empty = false;
  bool unbounded = false;
  double lo_nm = 0, hi_nm = 0;
};

class Spectrum {
 public:
  virtual ~Spectrum() = default;
  // ∫_a^b s(λ) dλ for a <= b, including the scale factor.
  double integral(double a_nm, double b_nm) const { return scale_ * raw_integral(a_nm, b_nm); }
  virtual SpectralSupport support() const = 0;
  // The value at one wavelength, including the scale; a line has none (throws kasha::Error).
  double value(double nm) const { return scale_ * raw_value(nm); }
  // The largest value, including the scale (a line's is its integral): what range checks bound.
  double peak() const { return scale_ * raw_peak(); }
  void set_scale(double scale) { scale_ *= scale; }
  double scale() const { return scale_; }

 protected:
  virtual double raw_integral(double a_nm, double b_nm) const = 0;
  virtual double raw_value(double nm) const = 0;
  virtual double raw_peak() const = 0;

 private:
  double scale_ = 1.0;
};

using SpectrumPtr = std::shared_ptr<Spectrum>;

class ConstantSpectrum : public Spectrum {
 public:
  explicit ConstantSpectrum(double value) : value_(value) {}
  SpectralSupport support() const override;

 protected:
  double raw_integral(double a, double b) const override { return value_ * (b - a); }
  double raw_value(double) const override { return value_; }
  double raw_peak() const override { return value_; }

 private:
  double value_;
};

// Linear interpolation between samples, zero outside them. Wavelengths strictly increase and values
// are finite and non-negative (checked by the parser, which knows where the data came from).
class PiecewiseLinearSpectrum : public Spectrum {
 public:
  PiecewiseLinearSpectrum(std::vector<double> nm, std::vector<double> value);
  SpectralSupport support() const override;

 protected:
  double raw_integral(double a, double b) const override;
  double raw_value(double nm) const override;
  double raw_peak() const override;

 private:
  std::vector<double> nm_, value_;
};

// Peak value 1 at `center_nm`.
class GaussianSpectrum : public Spectrum {
 public:
  GaussianSpectrum(double center_nm, double fwhm_nm);
  SpectralSupport support() const override;

 protected:
  double raw_integral(double a, double b) const override;
  double raw_value(double nm) const override;
  double raw_peak() const override { return 1.0; }

 private:
  double center_, sigma_;
};

// Planck's law, spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹.
class BlackbodySpectrum : public Spectrum {
 public:
  explicit BlackbodySpectrum(double kelvin) : kelvin_(kelvin) {}
  SpectralSupport support() const override;

 protected:
  double raw_integral(double a, double b) const override;
  double raw_value(double nm) const override;
  double raw_peak() const override;

 private:
  double kelvin_;
};

// Unit integral concentrated at one wavelength: all of it lands in the bin [lo, hi) that holds it.
class LineSpectrum : public Spectrum {
 public:
  explicit LineSpectrum(double nm) : nm_(nm) {}
  SpectralSupport support() const override { return {false, false, nm_, nm_}; }
  double wavelength() const { return nm_; }

 protected:
  double raw_integral(double a, double b) const override {
    return (nm_ >= a && nm_ < b) ? 1.0 : 0.0;
  }
  double raw_value(double nm) const override;
  double raw_peak() const override { return 1.0; }

 private:
  double nm_;
};

}  // namespace kasha
