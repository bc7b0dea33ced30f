#pragma once
// χ² goodness-of-fit tests for the kernel unit tests, and the helpers they share: uniforms drawn
// on the host from fixed seeds, frames, cells of a triangle in barycentric space. Cells expected
// below 5 are pooled; a fit fails when p < kMinP, and a wrong density must give p < kMinP.
#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "shared/shared_types.h"

namespace kasha::test {

constexpr double kMinP = 1e-4;

// `count` uniforms in [0, 1) with 24 random bits each (so never 1), from a fixed seed.
std::vector<float> uniforms(size_t count, std::uint32_t seed);

// Q(a, x) = Γ(a, x) / Γ(a), the regularized upper incomplete gamma function.
double gamma_q(double a, double x);

struct Chi2 {
  double statistic = 0;
  int df = 0;
  double p = 1;
  double stray = 0;  // samples in cells of zero expected count
};

// Pearson's χ² test of observed counts against expected counts (the same total). Cells are taken
// in increasing expected count; those expected below 5 are pooled with the next until the pool
// reaches 5. A sample in a cell of zero expected count makes p = 0.
Chi2 chi2_test(const std::vector<double>& observed, const std::vector<double>& expected);

// Runs the test, prints its figures and fails when the samples contradict the density.
void expect_fits(const std::string& what, const std::vector<double>& observed,
                 const std::vector<double>& expected);

// The same samples against a wrong density: the test must be able to tell.
void expect_rejects(const std::string& what, const std::vector<double>& observed,
                    const std::vector<double>& wrong);

// The 3-vector at v[i], v[i + 1], v[i + 2].
Eigen::Vector3d at(const std::vector<float>& v, size_t i);

// Any orthonormal frame (s, t) about the unit vector n.
void frame(const Eigen::Vector3d& n, Eigen::Vector3d& s, Eigen::Vector3d& t);

// The cell of x among n equal cells of [lo, hi), clamped to 0 .. n-1.
int cell_of(double x, double lo, double hi, int n);

// Cells of the triangle b1, b2 >= 0, b1 + b2 <= 1 in barycentric space: squares of side 1/k, the
// ones on the hypotenuse cut in half (cell i * k + j: b1 in [i, i+1) / k, b2 in [j, j+1) / k);
// -1 outside.
int triangle_cell(double b1, double b2, int k);

// The share of the area of each triangle cell (uniform density).
std::vector<double> triangle_cell_area(int k);

// A kernel triangle with the given vertices.
KTriangle triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   int emitter, int prim);

}  // namespace kasha::test
