#include "analytic_floor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_support.h"
#include "test_support.h"

namespace kasha::test {

using Eigen::Vector3d;

std::string floor_scene(const std::string& name, const std::string& floor,
                        const std::string& lights, const std::string& extra,
                        const std::string& floor_keys, const std::string& shapes) {
  std::ostringstream s;
  s << R"({"kasha_scene": 1,
  "wavelengths": {"min_nm": 400, "max_nm": 700, "bin_nm": 50},
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 60,
             "width": )"
    << kFloorSize << R"(, "height": )" << kFloorSize << R"(},
  "materials": {"floor": )"
    << floor << R"(},
  "lights": [)"
    << lights << "],\n"
    << (extra.empty() ? "" : extra + ",\n")
    << R"(  "shapes": [{"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "floor")"
    << (floor_keys.empty() ? "" : ", " + floor_keys) << "}" << (shapes.empty() ? "" : ", " + shapes)
    << "]\n}";
  return write_file(name + ".json", s.str());
}

Vector3d floor_point(const KCamera& c, double x, double y) {
  Vector3d o(c.position[0], c.position[1], c.position[2]);
  Vector3d f(c.forward[0], c.forward[1], c.forward[2]), r(c.right[0], c.right[1], c.right[2]),
      u(c.up[0], c.up[1], c.up[2]);
  Vector3d d = f + (2 * x / c.width - 1) * r + (1 - 2 * y / c.height) * u;
  return o + d * (-o.z() / d.z());
}

void expect_floor(const std::string& scene, const std::string& integrator,
                  const FloorRadiance& radiance, int spp, long long photons, int passes) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = passes;
  s.integrator_settings.spp = spp;
  s.integrator_settings.photons = photons;
  RenderResult r = render_scene(scene, s);
  const KCamera cam = r.scene.camera.to_kernel();
  const size_t N = r.scene.grid.bins;
  constexpr int kRings = 4, kSub = 16, kSize = kFloorSize;
  std::vector<double> sum(kRings, 0), sum2(kRings, 0), truth(kRings, 0), count(kRings, 0);
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      std::vector<double> want(N, 0.0);
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          Vector3d x = floor_point(cam, px + (a + 0.5) / kSub, py + (b + 0.5) / kSub);
          for (size_t i = 0; i < N; ++i) want[i] += radiance(r.scene, x, int(i)) / (kSub * kSub);
        }
      double dx = px + 0.5 - kSize / 2.0, dy = py + 0.5 - kSize / 2.0;
      int ring = std::min(kRings - 1, int(std::sqrt(dx * dx + dy * dy) / (kSize / 2.0) * kRings));
      for (size_t i = 0; i < N; ++i) {
        double d = r.image.spectral[(py * kSize + px) * N + i] - want[i];
        sum[ring] += d;
        sum2[ring] += d * d;
        truth[ring] += want[i];
        count[ring] += 1;
      }
    }
  for (int k = 0; k < kRings; ++k) {
    double n = count[k], mean = sum[k] / n, var = sum2[k] / n - mean * mean;
    double se = std::sqrt(std::max(var, 0.0) / (n - 1)), t = truth[k] / n;
    std::printf("%s %s ring %d: truth %.5g, residual %+.3g (SE %.2g)\n", scene.c_str(),
                integrator.c_str(), k, t, mean, se);
    EXPECT_LT(std::abs(mean), 4 * se + 0.01 * t)
        << integrator << " ring " << k << ": truth " << t << ", residual " << mean << " ± " << se;
  }
  EXPECT_EQ(r.rejected, 0);
}

}  // namespace kasha::test
