#pragma once
// Isotropic GGX in a frame whose z is the surface's normal (pbrt-v4's TrowbridgeReitz), in
// double: the host's tables of rough coats and layered metals integrate with it.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kasha {

struct HostGgx {
  double alpha;
  double lambda(const Eigen::Vector3d& w) const {
    const double c2 = w.z() * w.z(), t2 = std::max(0.0, 1 - c2) / c2;
    return (std::sqrt(1 + alpha * alpha * t2) - 1) / 2;
  }
  double g1(const Eigen::Vector3d& w) const { return 1 / (1 + lambda(w)); }
  double g(const Eigen::Vector3d& wo, const Eigen::Vector3d& wi) const {
    return 1 / (1 + lambda(wo) + lambda(wi));
  }
  // A normal visible from w (Heitz 2018), u in [0, 1)².
  Eigen::Vector3d sample_visible(const Eigen::Vector3d& w, double u0, double u1) const {
    const Eigen::Vector3d wh = Eigen::Vector3d(alpha * w.x(), alpha * w.y(), w.z()).normalized();
    const Eigen::Vector3d t1 = wh.z() < 0.99999 ? Eigen::Vector3d(0, 0, 1).cross(wh).normalized()
                                                : Eigen::Vector3d(1, 0, 0);
    const Eigen::Vector3d t2 = wh.cross(t1);
    const double r = std::sqrt(u0), phi = 2 * M_PI * u1;
    double px = r * std::cos(phi), py = r * std::sin(phi);
    const double h = std::sqrt(std::max(0.0, 1 - px * px));
    py = (1 - (1 + wh.z()) / 2) * h + (1 + wh.z()) / 2 * py;
    const double pz = std::sqrt(std::max(0.0, 1 - px * px - py * py));
    const Eigen::Vector3d nh = px * t1 + py * t2 + pz * wh;
    return Eigen::Vector3d(alpha * nh.x(), alpha * nh.y(), std::max(1e-9, nh.z())).normalized();
  }
};

}  // namespace kasha
