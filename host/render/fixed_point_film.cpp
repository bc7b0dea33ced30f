#include "render/fixed_point_film.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kasha {

int fixed_point_shift(const KernelSceneData& scene, const std::vector<float>& cmf, bool spectral) {
  // ℓ: the scene's bounding-box diagonal, the camera included, bounds every splat's distance r.
  Eigen::AlignedBox3d box;
  const float* c = scene.camera.position;
  box.extend(Eigen::Vector3d(c[0], c[1], c[2]));
  for (const KTriangle& t : scene.bvh.triangles)
    for (const float* v : {t.v0, t.v1, t.v2}) box.extend(Eigen::Vector3d(v[0], v[1], v[2]));
  const double length = box.diagonal().norm();
  const KCamera& cam = scene.camera;
  const double pixel_area = 4.0 * Eigen::Vector3d(cam.right[0], cam.right[1], cam.right[2]).norm() *
                            Eigen::Vector3d(cam.up[0], cam.up[1], cam.up[2]).norm() /
                            (static_cast<double>(cam.width) * cam.height) /
                            // An orthographic pixel's area is the world's, its splats 1/A_pixel.
                            (cam.type == KASHA_CAMERA_ORTHOGRAPHIC ? length * length : 1.0);
  // The largest film-row weight of a bin: x̄ȳz̄·Δλ on an XYZ film, 1 on a spectral one.
  double weight = spectral ? 1.0 : 0.0;
  for (float w : cmf) weight = std::max(weight, static_cast<double>(w));
  // V: a pass's whole power P splatted into one pixel from distance ℓ,
  // (P·weight/(πΔλ))·1/(ℓ²A_pixel). A photon's splat (P/photons ≥ 2^-31 P) is then ≥ 2^-31 V·(its
  // share), far above the unit 2^-64 V; a pass's pixel passes 2^63 V only if its photons come
  // ~3·10^9 times closer than ℓ.
  const double v =
      scene.total_power * weight / (M_PI * scene.bin_nm * length * length * pixel_area);
  if (!(v > 0 && std::isfinite(v))) return 0;  // no light: nothing is splatted
  return 64 - std::ilogb(v);
}

double fixed_point_value(uint64_t lo, uint64_t hi, int shift) {
  return std::ldexp(static_cast<double>(hi), 64 - shift) +
         std::ldexp(static_cast<double>(lo), -shift);
}

}  // namespace kasha
