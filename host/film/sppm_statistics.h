#pragma once
// The per-pixel statistics of stochastic progressive photon mapping (Hachisuka & Jensen 2009):
// radius R, photon count n and shrunk flux τ. After a pass that found m photons with flux φ inside
// R: n' = n + αm, R' = R·sqrt(n'/(n + m)), τ' = (τ + φ)·R'²/R². After k passes the radiance is
// τ/(k·π·R²·Δλ).
#include <vector>

#include "film/pass_result.h"

namespace kasha {

class SppmStatistics {
 public:
  SppmStatistics(size_t pixels, int rows);
  void update(const GatherPass& pass);
  const std::vector<double>& radius() const { return radius_; }
  int passes() const { return passes_; }
  // Radiance per nm of row r at pixel p (0 where no visible point was ever found).
  double radiance(size_t p, int r, double bin_nm) const;

 private:
  size_t pixels_;
  int rows_;
  int passes_ = 0;
  std::vector<double> radius_, count_, tau_;
};

}  // namespace kasha
