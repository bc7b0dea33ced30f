#include "film/sppm_statistics.h"

#include <cmath>
#include <stdexcept>

namespace kasha {

SppmStatistics::SppmStatistics(size_t pixels, int rows)
    : pixels_(pixels),
      rows_(rows),
      radius_(pixels, 0.0),
      count_(pixels, 0.0),
      tau_(pixels * rows, 0.0) {}

void SppmStatistics::update(const GatherPass& g) {
  if (g.radius.size() != pixels_ || g.found.size() != pixels_ || g.flux.size() != pixels_ * rows_)
    throw std::logic_error("photon gather has the wrong size");
  ++passes_;
  for (size_t p = 0; p < pixels_; ++p) {
    const int m = g.found[p];
    if (m <= 0) {
      if (radius_[p] == 0) radius_[p] = g.radius[p];  // the pixel's first visible point
      continue;
    }
    const double r = g.radius[p];
    double n_new = count_[p] + g.alpha * m;
    double r_new = r * std::sqrt(n_new / (count_[p] + m));
    double shrink = (r_new * r_new) / (r * r);
    for (int k = 0; k < rows_; ++k)
      tau_[p * rows_ + k] = (tau_[p * rows_ + k] + g.flux[p * rows_ + k]) * shrink;
    count_[p] = n_new;
    radius_[p] = r_new;
  }
}

double SppmStatistics::radiance(size_t p, int r, double bin_nm) const {
  if (passes_ == 0 || radius_[p] <= 0) return 0.0;
  return tau_[p * rows_ + r] / (passes_ * M_PI * radius_[p] * radius_[p] * bin_nm);
}

}  // namespace kasha
