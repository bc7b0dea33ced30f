#pragma once
// Accumulates a render's passes per pixel in double precision. Film rows are X,Y,Z, or the N bins
// of a spectral film (XYZ is then derived from the bins on output). Every integrator's pass
// arrives as a PassResult and is accumulated the same way: sums add up, counters add up, and
// photon mapping's gathers update the SPPM statistics that the image adds to the sums' mean.
#include <vector>

#include "color/cie_observer.h"
#include "film/image.h"
#include "film/pass_result.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

class Film {
 public:
  // exposure: what image() multiplies the estimate by (the camera's "exposure").
  Film(int width, int height, const WavelengthGrid& grid, bool spectral, double exposure = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  int rows() const { return spectral_ ? grid_.bins : 3; }
  bool spectral() const { return spectral_; }
  const WavelengthGrid& grid() const { return grid_; }
  size_t pixels() const { return static_cast<size_t>(width_) * height_; }

  void accumulate(const PassResult& pass);
  // The fewest samples any pixel has (pixels differ when a pass was cut short).
  long long samples_per_pixel() const { return samples_; }
  double work_passes() const { return work_; }  // passes, counting a cut-short one by its fraction
  int passes() const { return passes_; }
  // Every pass's counters, added (PassCounters::add).
  const PassCounters& counters() const { return counters_; }

  Image image() const;  // the current estimate

 private:
  double exposure_ = 1;
  int width_, height_;
  WavelengthGrid grid_;
  bool spectral_;
  BinnedObserver observer_;
  std::vector<double> sum_;
  std::vector<long long> pixel_samples_;
  long long samples_ = 0;
  double work_ = 0;
  int passes_ = 0;
  PassCounters counters_;
  KeptImage kept_;
};

}  // namespace kasha
