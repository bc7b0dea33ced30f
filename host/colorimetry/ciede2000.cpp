#include "colorimetry/ciede2000.h"

#include <cmath>

namespace kasha {

namespace {

constexpr double kPi = 3.14159265358979323846;

double degrees(double rad) {
  return rad * 180.0 / kPi;
}
double radians(double deg) {
  return deg * kPi / 180.0;
}

// Hue angle in [0, 360); 0 for a neutral colour (Sharma et al. eq. 4).
double hue_deg(double a, double b) {
  if (a == 0 && b == 0) return 0;
  double h = degrees(std::atan2(b, a));
  return h < 0 ? h + 360 : h;
}

}  // namespace

double ciede2000(const Vec3d& lab1, const Vec3d& lab2, double kL, double kC, double kH) {
  const double L1 = lab1[0], a1 = lab1[1], b1 = lab1[2];
  const double L2 = lab2[0], a2 = lab2[1], b2 = lab2[2];
  // a' stretches the a axis near neutral (G), where CIELAB's hue spacing is too narrow.
  const double C_mean = 0.5 * (std::hypot(a1, b1) + std::hypot(a2, b2));
  const double C7 = std::pow(C_mean, 7);
  const double G = 0.5 * (1 - std::sqrt(C7 / (C7 + std::pow(25.0, 7))));
  const double ap1 = (1 + G) * a1, ap2 = (1 + G) * a2;
  const double Cp1 = std::hypot(ap1, b1), Cp2 = std::hypot(ap2, b2);
  const double hp1 = hue_deg(ap1, b1), hp2 = hue_deg(ap2, b2);

  const double dL = L2 - L1, dC = Cp2 - Cp1;
  // Hue difference the short way round; zero when either colour is neutral.
  double dh = 0;
  if (Cp1 * Cp2 != 0) {
    dh = hp2 - hp1;
    if (dh > 180)
      dh -= 360;
    else if (dh < -180)
      dh += 360;
  }
  const double dH = 2 * std::sqrt(Cp1 * Cp2) * std::sin(radians(dh / 2));

  const double Lp = 0.5 * (L1 + L2), Cp = 0.5 * (Cp1 + Cp2);
  // Mean hue, also the short way round (Sharma et al. eq. 14).
  double hp = hp1 + hp2;
  if (Cp1 * Cp2 != 0) {
    if (std::abs(hp1 - hp2) <= 180)
      hp = 0.5 * (hp1 + hp2);
    else
      hp = hp1 + hp2 < 360 ? 0.5 * (hp1 + hp2 + 360) : 0.5 * (hp1 + hp2 - 360);
  }
  const double T = 1 - 0.17 * std::cos(radians(hp - 30)) + 0.24 * std::cos(radians(2 * hp)) +
                   0.32 * std::cos(radians(3 * hp + 6)) - 0.20 * std::cos(radians(4 * hp - 63));
  const double d_theta = 30 * std::exp(-std::pow((hp - 275) / 25, 2));
  const double Cp7 = std::pow(Cp, 7);
  const double RC = 2 * std::sqrt(Cp7 / (Cp7 + std::pow(25.0, 7)));
  const double L50 = (Lp - 50) * (Lp - 50);
  const double SL = 1 + 0.015 * L50 / std::sqrt(20 + L50);
  const double SC = 1 + 0.045 * Cp, SH = 1 + 0.015 * Cp * T;
  const double RT = -std::sin(radians(2 * d_theta)) * RC;

  const double l = dL / (kL * SL), c = dC / (kC * SC), h = dH / (kH * SH);
  return std::sqrt(l * l + c * c + h * h + RT * c * h);
}

}  // namespace kasha
