#include "measure/rank1_fit.h"

#include <cmath>

namespace kasha {

Rank1Fit fit_rank1_nonnegative(const Eigen::MatrixXd& F, const Eigen::MatrixXd& known) {
  const Eigen::MatrixXd WF = known.cwiseProduct(F);
  Rank1Fit fit;
  // Start from the mean emission shape; each half-step is the exact non-negative least-squares
  // solution for one factor with the other fixed, so the masked error never increases.
  fit.e = WF.rowwise().sum().cwiseMax(0.0);
  if (fit.e.maxCoeff() <= 0) fit.e.setOnes();
  fit.a = Eigen::VectorXd::Zero(F.cols());
  double previous = INFINITY;
  for (fit.iterations = 1; fit.iterations <= 500; ++fit.iterations) {
    Eigen::VectorXd e2 = fit.e.cwiseProduct(fit.e);
    for (Eigen::Index i = 0; i < F.cols(); ++i) {
      double den = known.col(i).dot(e2);
      fit.a[i] = den > 0 ? std::max(0.0, WF.col(i).dot(fit.e) / den) : 0.0;
    }
    Eigen::VectorXd a2 = fit.a.cwiseProduct(fit.a);
    for (Eigen::Index o = 0; o < F.rows(); ++o) {
      double den = known.row(o).dot(a2);
      fit.e[o] = den > 0 ? std::max(0.0, WF.row(o).dot(fit.a) / den) : 0.0;
    }
    double peak = fit.e.maxCoeff();
    if (peak <= 0) break;  // nothing fluoresces
    fit.e /= peak;
    fit.a *= peak;
    double err = (known.cwiseProduct(F - fit.e * fit.a.transpose())).squaredNorm();
    if (previous - err <= 1e-12 * previous) break;
    previous = err;
  }
  const Eigen::MatrixXd model = fit.e * fit.a.transpose();
  double norm = WF.norm();
  fit.relative_residual = norm > 0 ? (known.cwiseProduct(F - model)).norm() / norm : 0.0;
  double level = 0.1 * model.maxCoeff(), diff2 = 0, data2 = 0;
  for (Eigen::Index o = 0; o < F.rows(); ++o)
    for (Eigen::Index i = 0; i < F.cols(); ++i)
      if (known(o, i) > 0 && level > 0 && (model(o, i) > level || std::abs(F(o, i)) > level)) {
        diff2 += (F(o, i) - model(o, i)) * (F(o, i) - model(o, i));
        data2 += F(o, i) * F(o, i);
      }
  fit.signal_residual = data2 > 0 ? std::sqrt(diff2 / data2) : 0.0;
  return fit;
}

}  // namespace kasha
