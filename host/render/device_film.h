#pragma once
// The film on a device: the tables every kernel reads (the film rows' weights C and the branch
// importance per bin), uploaded once in one buffer and bound in the order of KASHA_FILM_PARAMS
// (kernels/film/film_view.h) with the job's ray counters, and the per-pixel sums buffer of kernels
// whose work items own a pixel.
#include <vector>

#include "film/film.h"
#include "opencl/device.h"

namespace kasha {

class DeviceFilm {
 public:
  DeviceFilm(ClContext& cl, const Film& film);

  size_t pixels() const { return pixels_; }
  int rows() const { return rows_; }
  bool spectral() const { return spectral_; }
  // Per-bin XYZ weights (x̄ȳz̄ times the bin width), 3 × N, as the kernels read them.
  const std::vector<float>& cmf() const { return cmf_; }
  // The film's tables on the device: C first, so kernels that read only C take this buffer too.
  const cl::Buffer& cmf_buffer() const { return tables_; }
  // Per bin, what it is worth to the film when a path chooses a branch: x̄ + ȳ + z̄ times the bin
  // width plus 5 % of its peak, so bins no row sees directly (UV feeding fluorescence, a spectral
  // film's edges) keep a chance and the estimator stays unbiased for every row.
  const std::vector<float>& importance() const { return importance_; }

  // Sets KASHA_FILM_PARAMS from argument `first` on; returns the next argument's index.
  int bind(cl::Kernel& kernel, int first) const;

  // The closest-hit and shadow rays the job's kernels traced since the last call; zeroes them.
  struct RayCounts {
    double closest = 0, shadow = 0;
  };
  RayCounts take_ray_counts();
  // Bytes of the tables and counters on the device (the per-pixel sums apart).
  size_t table_bytes() const {
    return (cmf_.size() + importance_.size()) * sizeof(float) + 4 * sizeof(cl_uint);
  }

  // pixels × rows floats that kernels add to with film_add; zeroed by clear_pixel_sums.
  cl::Buffer& pixel_sums();
  void clear_pixel_sums();
  std::vector<double> read_pixel_sums();

 private:
  ClContext& cl_;
  size_t pixels_;
  int rows_;
  bool spectral_;
  std::vector<float> cmf_, importance_;
  cl::Buffer tables_;  // cmf_ then importance_ (KASHA_FILM_PARAMS' film_tables)
  cl::Buffer sums_;
  cl::Buffer ray_counts_;  // closest, shadow: (low, high) 32-bit words each
};

}  // namespace kasha
