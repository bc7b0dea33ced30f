#pragma once
// Accumulates a render's passes per pixel in double precision. Film rows are X,Y,Z, or the N bins
// of a spectral film (XYZ is then derived from the bins on output).
#include <vector>

#include "color/cie_observer.h"
#include "film/image.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

class Film {
 public:
  Film(int width, int height, const WavelengthGrid& grid, bool spectral);

  int rows() const { return spectral_ ? grid_.bins : 3; }
  bool spectral() const { return spectral_; }
  size_t pixels() const { return static_cast<size_t>(width_) * height_; }

  // Adds a pass: `sums` holds pixels × rows values, each the sum of `samples_per_pixel` samples.
  void add_pass(const std::vector<float>& sums, long long samples_per_pixel);
  long long samples_per_pixel() const { return samples_; }
  // Replaces the film's content by a per-pixel estimate (pixels × rows) worth `samples` samples,
  // for integrators whose estimate is not a plain average of passes (photon mapping).
  void set_estimate(const std::vector<double>& mean, long long samples);
  // Per-bin XYZ weights (x̄ȳz̄ times bin width), 3 × N, as kernels take them.
  std::vector<float> cmf_weights() const;

  Image image() const;  // the current estimate (mean over samples)

 private:
  int width_, height_;
  WavelengthGrid grid_;
  bool spectral_;
  BinnedObserver observer_;
  std::vector<double> sum_;
  long long samples_ = 0;
};

}  // namespace kasha
