#pragma once
// The best non-negative rank-1 approximation e·aᵀ of a matrix over a mask of known entries
// (masked alternating least squares): Kasha's rule says a fluorophore's re-radiation is rank-1.
#include <Eigen/Dense>

namespace kasha {

struct Rank1Fit {
  Eigen::VectorXd e;             // rows; scaled so that max(e) = 1
  Eigen::VectorXd a;             // columns
  double relative_residual = 0;  // ‖W∘(F − e aᵀ)‖ / ‖W∘F‖ over the known entries
  // The same over the known entries that carry signal (fit or data above 10 % of the fit's peak):
  // unlike the first, it does not fall as empty, noisy parts of the matrix grow.
  double signal_residual = 0;
  int iterations = 0;
};

// `known` holds 1 where F is known and 0 where it is not (band, second-order peaks).
Rank1Fit fit_rank1_nonnegative(const Eigen::MatrixXd& F, const Eigen::MatrixXd& known);

}  // namespace kasha
