#include "film/film.h"

#include <stdexcept>

namespace kasha {

Film::Film(int width, int height, const WavelengthGrid& grid, bool spectral)
    : width_(width),
      height_(height),
      grid_(grid),
      spectral_(spectral),
      observer_(grid),
      sum_(pixels() * rows(), 0.0) {}

void Film::add_pass(const std::vector<float>& sums, long long samples_per_pixel) {
  if (sums.size() != sum_.size()) throw std::logic_error("film pass has the wrong size");
  for (size_t i = 0; i < sum_.size(); ++i) sum_[i] += sums[i];
  samples_ += samples_per_pixel;
}

void Film::set_estimate(const std::vector<double>& mean, long long samples) {
  if (mean.size() != sum_.size()) throw std::logic_error("film estimate has the wrong size");
  samples_ = samples;
  for (size_t i = 0; i < sum_.size(); ++i) sum_[i] = mean[i] * samples;
}

std::vector<float> Film::cmf_weights() const {
  std::vector<float> w(3 * grid_.bins);
  for (int i = 0; i < grid_.bins; ++i) {
    w[i] = static_cast<float>(observer_.x[i] * grid_.bin_nm);
    w[grid_.bins + i] = static_cast<float>(observer_.y[i] * grid_.bin_nm);
    w[2 * grid_.bins + i] = static_cast<float>(observer_.z[i] * grid_.bin_nm);
  }
  return w;
}

Image Film::image() const {
  Image img;
  img.width = width_;
  img.height = height_;
  img.grid = grid_;
  img.xyz.assign(3 * pixels(), 0.0f);
  double inv = samples_ > 0 ? 1.0 / samples_ : 0.0;
  if (spectral_) img.spectral.assign(pixels() * grid_.bins, 0.0f);
  for (size_t p = 0; p < pixels(); ++p) {
    if (spectral_) {
      std::vector<double> bins(grid_.bins);
      for (int i = 0; i < grid_.bins; ++i) {
        bins[i] = sum_[p * grid_.bins + i] * inv;
        img.spectral[p * grid_.bins + i] = static_cast<float>(bins[i]);
      }
      auto xyz = observer_.xyz(bins, grid_.bin_nm);
      for (int k = 0; k < 3; ++k) img.xyz[3 * p + k] = static_cast<float>(xyz[k]);
    } else {
      for (int k = 0; k < 3; ++k) img.xyz[3 * p + k] = static_cast<float>(sum_[3 * p + k] * inv);
    }
  }
  return img;
}

}  // namespace kasha
