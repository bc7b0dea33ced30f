#include "chi2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>

namespace kasha::test {

using Eigen::Vector3d;

std::vector<float> uniforms(size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<float> u(count);
  for (float& x : u) x = static_cast<float>(rng() >> 8) * 0x1p-24f;
  return u;
}

// The series for P(a, x) below x = a + 1, the continued fraction (modified Lentz) above
// (Numerical Recipes §6.2).
double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double front = std::exp(-x + a * std::log(x) - std::lgamma(a));
  if (x < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < 10000 && term > sum * 1e-16; ++n) sum += term *= x / (a + n);
    return std::max(0.0, 1 - sum * front);
  }
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    if (std::abs(d * c - 1) < 1e-16) break;
  }
  return front * h;
}

Chi2 chi2_test(const std::vector<double>& observed, const std::vector<double>& expected) {
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  Chi2 r;
  double pool_o = 0, pool_e = 0;
  int cells = 0;
  for (size_t i : order) {
    const double o = observed[i], e = expected[i];
    if (e <= 0) {
      r.stray += o;
    } else if (e < 5 || (pool_e > 0 && pool_e < 5)) {
      pool_o += o, pool_e += e;
    } else {
      r.statistic += (o - e) * (o - e) / e, ++cells;
    }
  }
  if (pool_e > 0) r.statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e, ++cells;
  r.df = cells - 1;
  if (r.stray > 0) {
    r.statistic = INFINITY;
    r.p = 0;
  } else {
    r.p = gamma_q(r.df / 2.0, r.statistic / 2);
  }
  return r;
}

void expect_fits(const std::string& what, const std::vector<double>& observed,
                 const std::vector<double>& expected) {
  Chi2 r = chi2_test(observed, expected);
  std::printf("[ chi2     ] %s: chi2 = %.1f, df = %d, p = %.3g\n", what.c_str(), r.statistic, r.df,
              r.p);
  EXPECT_GE(r.p, kMinP) << what << ": chi2 = " << r.statistic << ", df = " << r.df
                        << ", samples in cells of zero density: " << r.stray;
}

void expect_rejects(const std::string& what, const std::vector<double>& observed,
                    const std::vector<double>& wrong) {
  Chi2 r = chi2_test(observed, wrong);
  std::printf("[ chi2     ] %s (wrong density): chi2 = %.1f, df = %d, p = %.3g\n", what.c_str(),
              r.statistic, r.df, r.p);
  EXPECT_LT(r.p, kMinP) << what << ": the wrong density was not rejected";
}

Vector3d at(const std::vector<float>& v, size_t i) {
  return Vector3d(v[i], v[i + 1], v[i + 2]);
}

void frame(const Vector3d& n, Vector3d& s, Vector3d& t) {
  s = (std::abs(n.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY()).cross(n).normalized();
  t = n.cross(s);
}

int cell_of(double x, double lo, double hi, int n) {
  return std::clamp(static_cast<int>((x - lo) / (hi - lo) * n), 0, n - 1);
}

int triangle_cell(double b1, double b2, int k) {
  const double slack = 1e-6;  // float rounding
  if (b1 < -slack || b2 < -slack || b1 + b2 > 1 + slack) return -1;
  int i = cell_of(b1, 0, 1, k), j = cell_of(b2, 0, 1, k);
  if (i + j >= k) {  // rounding past the hypotenuse: the diagonal cell next to it
    if (i >= j)
      i = k - 1 - j;
    else
      j = k - 1 - i;
  }
  return i * k + j;
}

std::vector<double> triangle_cell_area(int k) {
  std::vector<double> share(k * k, 0.0);
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) share[i * k + j] = (i + j == k - 1 ? 1.0 : 2.0) / (k * k);
  return share;
}

KTriangle triangle(const Vector3d& a, const Vector3d& b, const Vector3d& c, int emitter, int prim) {
  KTriangle t{};
  for (int k = 0; k < 3; ++k) {
    t.v0[k] = static_cast<float>(a[k]);
    t.v1[k] = static_cast<float>(b[k]);
    t.v2[k] = static_cast<float>(c[k]);
  }
  t.emitter = emitter;
  t.prim = prim;
  return t;
}

}  // namespace kasha::test
