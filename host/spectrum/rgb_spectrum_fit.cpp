#include "spectrum/rgb_spectrum_fit.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace kasha {

namespace {

// Linear sRGB → XYZ, IEC 61966-2-1 at full precision (host/data/sRGB_XYZ_constants.txt).
constexpr double kRgbToXyz[3][3] = {{0.4123907993, 0.3575843394, 0.1804807884},
                                    {0.2126390059, 0.7151686788, 0.0721923154},
                                    {0.0193308187, 0.1191947798, 0.9505321522}};
// The sRGB white (D65, Y = 1).
constexpr double kWhite[3] = {0.4123907993 + 0.3575843394 + 0.1804807884, 1.0,
                              0.0193308187 + 0.1191947798 + 0.9505321522};

double lab_f(double t) {
  const double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

std::array<double, 3> xyz_lab(const std::array<double, 3>& xyz) {
  double fx = lab_f(xyz[0] / kWhite[0]), fy = lab_f(xyz[1] / kWhite[1]),
         fz = lab_f(xyz[2] / kWhite[2]);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double smoothstep(double x) {
  return x * x * (3 - 2 * x);
}

// The bound on the coefficients (over t in [0, 1]): pbrt-v4's rgb2spec_opt keeps them within
// 200, which leaves the darkest saturated colours (sRGB code values below ~10 in one channel
// alone) several ΔE off; their spectra must be narrow bumps, which takes larger coefficients.
constexpr double kMaxCoefficient = 10000;

// The fit works on t = (λ − min) / span in [0, 1], where the coefficients stay of order 1.
struct Normalized {
  const FitObserver& obs;
  double span() const { return obs.step_nm * (obs.x.size() - 1); }

  std::array<double, 3> lab(const SigmoidCoefficients& c) const {
    std::array<double, 3> xyz{0, 0, 0};
    double norm = 0;
    const size_t n = obs.x.size();
    for (size_t i = 0; i < n; ++i) {
      double t = double(i) / (n - 1), x = (c[0] * t + c[1]) * t + c[2];
      double s = 0.5 + x / (2 * std::sqrt(1 + x * x));
      double w = (i == 0 || i == n - 1) ? 0.5 : 1.0;  // trapezoid
      xyz[0] += w * s * obs.d65[i] * obs.x[i];
      xyz[1] += w * s * obs.d65[i] * obs.y[i];
      xyz[2] += w * s * obs.d65[i] * obs.z[i];
      norm += w * obs.d65[i] * obs.y[i];
    }
    for (double& v : xyz) v /= norm;
    return xyz_lab(xyz);
  }

  // Gauss–Newton from c towards the colour `target` (CIELAB); c holds the result. A step is taken
  // only as far as it lowers the residual (halved up to 20 times): at the edge of what smooth
  // spectra reach (dark saturated blues) the full step overshoots, and the fit must end at the
  // nearest colour it can make, not wherever the iteration wandered.
  void solve(const std::array<double, 3>& target, SigmoidCoefficients& c) const {
    auto residual = [&](const SigmoidCoefficients& x, std::array<double, 3>& r) {
      r = lab(x);
      double e = 0;
      for (int k = 0; k < 3; ++k) r[k] -= target[k], e += r[k] * r[k];
      return e;
    };
    std::array<double, 3> r;
    double err = residual(c, r);
    for (int it = 0; it < 50 && err > 1e-12; ++it) {
      double J[3][3];
      for (int j = 0; j < 3; ++j) {
        SigmoidCoefficients a = c, b = c;
        a[j] -= 1e-5;
        b[j] += 1e-5;
        std::array<double, 3> la = lab(a), lb = lab(b);
        for (int k = 0; k < 3; ++k) J[k][j] = (lb[k] - la[k]) / 2e-5;
      }
      // Solve J d = r by Cramer's rule (3 × 3).
      auto det3 = [](const double M[3][3]) {
        return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
               M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
               M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
      };
      const double det = det3(J);
      if (!(std::abs(det) > 1e-15)) return;
      double d[3];
      for (int j = 0; j < 3; ++j) {
        double M[3][3];
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) M[a][b] = b == j ? r[a] : J[a][b];
        d[j] = det3(M) / det;
      }
      bool better = false;
      for (double step = 1; step > 1e-6; step /= 2) {
        SigmoidCoefficients trial = {c[0] - step * d[0], c[1] - step * d[1], c[2] - step * d[2]};
        // Keep the polynomial from running off.
        double m = std::max({std::abs(trial[0]), std::abs(trial[1]), std::abs(trial[2])});
        if (m > kMaxCoefficient)
          for (double& v : trial) v *= kMaxCoefficient / m;
        std::array<double, 3> rt;
        double e = residual(trial, rt);
        if (e < err) {
          c = trial, r = rt, err = e, better = true;
          break;
        }
      }
      if (!better) return;
    }
  }

  // Back to λ in nm: c0 t² + c1 t + c2 with t = (λ − a) / w.
  SigmoidCoefficients to_nm(const SigmoidCoefficients& c) const {
    const double a = obs.min_nm, w = span();
    return {c[0] / (w * w), c[1] / w - 2 * c[0] * a / (w * w),
            c[0] * a * a / (w * w) - c[1] * a / w + c[2]};
  }
};

}  // namespace

double rgb_table_scale(int k, int res) {
  return smoothstep(smoothstep(double(k) / (res - 1)));
}

double rgb_table_ratio(int i, int res) {
  const double s = std::sin(M_PI / 2 * i / (res - 1));
  return s * s;
}

double rgb_table_ratio_index(double ratio, int res) {
  return std::asin(std::sqrt(std::clamp(ratio, 0.0, 1.0))) * 2 / M_PI * (res - 1);
}

double sigmoid_spectrum(const SigmoidCoefficients& c, double nm) {
  double x = (c[0] * nm + c[1]) * nm + c[2];
  if (std::isinf(x)) return x > 0 ? 1 : 0;
  return 0.5 + x / (2 * std::sqrt(1 + x * x));
}

std::array<double, 3> fit_rgb_lab(const std::array<double, 3>& rgb) {
  std::array<double, 3> xyz{0, 0, 0};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) xyz[r] += kRgbToXyz[r][k] * rgb[k];
  return xyz_lab(xyz);
}

std::array<double, 3> fit_spectrum_lab(const FitObserver& obs, const SigmoidCoefficients& c) {
  // The nm coefficients evaluated through t: λ = min + t·span.
  Normalized n{obs};
  const double a = obs.min_nm, w = n.span();
  SigmoidCoefficients ct = {c[0] * w * w, (2 * c[0] * a + c[1]) * w, (c[0] * a + c[1]) * a + c[2]};
  return n.lab(ct);
}

std::vector<float> fit_rgb_table(const FitObserver& obs, int res) {
  std::vector<float> table(size_t(3) * res * res * res * 3);
  Normalized n{obs};
  auto fit_rows = [&](int l, int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < res; ++i) {
        // From the middle of the z axis outwards, each fit starting where the last ended.
        const int start = res / 5;
        for (int dir : {+1, -1}) {
          SigmoidCoefficients c = {0, 0, 0};
          for (int k = dir > 0 ? start : start - 1; k >= 0 && k < res; k += dir) {
            double z = rgb_table_scale(k, res), x = rgb_table_ratio(i, res) * z,
                   y = rgb_table_ratio(j, res) * z;
            std::array<double, 3> rgb;
            rgb[l] = z;
            rgb[(l + 1) % 3] = x;
            rgb[(l + 2) % 3] = y;
            n.solve(fit_rgb_lab(rgb), c);
            SigmoidCoefficients nm = n.to_nm(c);
            size_t at = ((size_t(l) * res + k) * res + j) * res + i;
            for (int q = 0; q < 3; ++q) table[3 * at + q] = static_cast<float>(nm[q]);
          }
        }
      }
  };
  const int threads = std::max(1u, std::thread::hardware_concurrency());
  for (int l = 0; l < 3; ++l) {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back(fit_rows, l, res * t / threads, res * (t + 1) / threads);
    for (auto& th : pool) th.join();
  }
  return table;
}

}  // namespace kasha
