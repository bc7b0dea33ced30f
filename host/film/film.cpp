#include "film/film.h"

#include <algorithm>
#include <stdexcept>

namespace kasha {

Film::Film(int width, int height, const WavelengthGrid& grid, bool spectral, double exposure)
    : exposure_(exposure),
      width_(width),
      height_(height),
      grid_(grid),
      spectral_(spectral),
      observer_(grid),
      sum_(pixels() * rows(), 0.0),
      pixel_samples_(pixels(), 0) {}

void Film::accumulate(const PassResult& pass) {
  if (!pass.sums.empty()) {
    if (pass.sums.size() != sum_.size()) throw std::logic_error("film pass has the wrong size");
    for (size_t i = 0; i < sum_.size(); ++i) sum_[i] += pass.sums[i];
  }
  if (pass.pixel_samples.empty()) {
    for (long long& n : pixel_samples_) n += pass.samples;
  } else {
    if (pass.pixel_samples.size() != pixels())
      throw std::logic_error("film pass has the wrong size");
    for (size_t p = 0; p < pixels(); ++p) pixel_samples_[p] += pass.pixel_samples[p];
  }
  samples_ =
      pixel_samples_.empty() ? 0 : *std::min_element(pixel_samples_.begin(), pixel_samples_.end());
  ++passes_;
  work_ += pass.fraction;
  counters_.add(pass.counters);
  if (pass.kept) kept_ = pass.kept;
}

Image Film::image() const {
  Image img;
  img.width = width_;
  img.height = height_;
  img.grid = grid_;
  img.xyz.assign(3 * pixels(), 0.0f);
  const int R = rows();
  if (spectral_) img.spectral.assign(pixels() * grid_.bins, 0.0f);
  std::vector<double> value(R);
  const std::vector<float> kept = kept_ ? kept_() : std::vector<float>{};
  if (kept_ && kept.size() != pixels() * R) throw std::logic_error("kept image has the wrong size");
  for (size_t p = 0; p < pixels(); ++p) {
    const double inv = pixel_samples_[p] > 0 ? 1.0 / pixel_samples_[p] : 0.0;
    for (int r = 0; r < R; ++r) {
      value[r] = sum_[p * R + r] * inv;
      if (!kept.empty()) value[r] += kept[p * R + r];
      value[r] *= exposure_;
    }
    if (spectral_) {
      for (int i = 0; i < R; ++i) img.spectral[p * R + i] = static_cast<float>(value[i]);
      auto xyz = observer_.xyz(value, grid_.bin_nm);
      for (int k = 0; k < 3; ++k) img.xyz[3 * p + k] = static_cast<float>(xyz[k]);
    } else {
      for (int k = 0; k < 3; ++k) img.xyz[3 * p + k] = static_cast<float>(value[k]);
    }
  }
  return img;
}

}  // namespace kasha
