// Dispersion (docs/materials.md#dispersion): a prism of SF11 glass between the camera and a thin
// lamp strip. Each wavelength bends by its own index, so the camera sees the strip at a different
// angle in every bin. The test traces the same rays through the prism in double with Snell's law
// per bin (independently of the kernels) and compares, bin by bin, the column where the strip
// appears. Also: the named glasses' indices at the d line against their catalogue values, and the
// weights of the bin choice (diagonal and rank-1 paths, photons) in the fluorescent furnace.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "material/glasses.h"
#include "render_support.h"
#include "scene/scene.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

// The refracted direction of unit d through a surface with unit normal n on d's side (eta: far
// index over near), or nothing under total internal reflection.
std::optional<Vector3d> refract(const Vector3d& d, const Vector3d& n, double eta) {
  double cos_i = -d.dot(n), sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return std::nullopt;
  return (d / eta + (cos_i / eta - std::sqrt(1 - sin2_t)) * n).normalized();
}

// An infinite prism along y: its cross-section a triangle in xz, faces as (point, outward normal).
struct Prism {
  std::array<Vector3d, 3> v;  // y = 0
  Vector3d normal(int f) const {
    Vector3d e = v[(f + 1) % 3] - v[f], n(e.z(), 0, -e.x());
    Vector3d centre = (v[0] + v[1] + v[2]) / 3;
    if (n.dot(v[f] - centre) < 0) n = -n;
    return n.normalized();
  }
  // Entry (max over faces facing the ray) or exit (min over faces facing away) along o + t d.
  std::pair<double, int> cross(const Vector3d& o, const Vector3d& d, bool entering) const {
    double best = entering ? -INFINITY : INFINITY;
    int face = -1;
    for (int f = 0; f < 3; ++f) {
      Vector3d n = normal(f);
      double dn = d.dot(n);
      if (dn == 0) continue;
      double t = (v[f] - o).dot(n) / dn;
      if (entering && dn < 0 && t > best) best = t, face = f;
      if (!entering && dn > 0 && t < best) best = t, face = f;
    }
    return {best, face};
  }
};

double fresnel(double cos_i, double m) {
  return fresnel_reference(cos_i, m);
}

struct Exit {
  Vector3d point, dir;
  double transmitted;  // (1 − F) at both faces
};

// The ray through the prism by Snell's law (index eta) and out.
std::optional<Exit> through(const Prism& p, Vector3d o, Vector3d d, double eta) {
  auto [t_in, f_in] = p.cross(o, d, true);
  auto [t_out0, f_out0] = p.cross(o, d, false);
  if (f_in < 0 || !(t_in < t_out0) || t_in <= 0) return std::nullopt;
  o += t_in * d;
  double T = 1 - fresnel(-d.dot(p.normal(f_in)), eta);
  auto inside = refract(d, p.normal(f_in), eta);
  if (!inside) return std::nullopt;
  d = *inside;
  auto [t_out, f_out] = p.cross(o, d, false);
  o += t_out * d;
  auto out = refract(d, -p.normal(f_out), 1 / eta);
  if (!out) return std::nullopt;  // total internal reflection: not this path
  T *= 1 - fresnel(d.dot(p.normal(f_out)), 1 / eta);
  return Exit{o, *out, T};
}

TEST(Dispersion, NamedGlassesHaveTheirCatalogueIndexAtTheDLine) {
  const std::vector<std::pair<std::string, double>> catalogue = {
      {"BK7", 1.5168}, {"fused_silica", 1.4585}, {"SF11", 1.7847}, {"water", 1.3334}};
  for (const auto& [name, nd] : catalogue) {
    SpectrumPtr s = named_glass(name);
    ASSERT_TRUE(s) << name;
    EXPECT_NEAR(s->value(587.56), nd, 2e-4) << name;
    EXPECT_GT(s->value(450), s->value(650)) << name << ": normal dispersion";
  }
  EXPECT_FALSE(named_glass("BK8"));
}

TEST(Dispersion, APrismBendsEachBinByItsOwnIndex) {
  // A prism of apex angle 40° 3 units ahead, turned so that the camera's central ray passes it
  // near minimum deviation (about 36° at 550 nm).
  Prism prism;
  const double turn = -110 * M_PI / 180, half_apex = 20 * M_PI / 180, side = 1.2;
  const double local[3][2] = {{0, 0.6},
                              {side * std::sin(half_apex), 0.6 - side * std::cos(half_apex)},
                              {-side * std::sin(half_apex), 0.6 - side * std::cos(half_apex)}};
  for (int k = 0; k < 3; ++k) {
    const double x = local[k][0], z = local[k][1];
    prism.v[k] = Vector3d(x * std::cos(turn) + z * std::sin(turn), 0,
                          -3 - x * std::sin(turn) + z * std::cos(turn));
  }
  SpectrumPtr sf11 = named_glass("SF11");
  // The strip: 4 units along the middle of the spectrum's exit ray, facing back along it.
  const Vector3d centre_dir = Vector3d(0, 0, -1);
  auto mid = through(prism, Vector3d::Zero(), centre_dir, sf11->value(550));
  ASSERT_TRUE(mid) << "the central ray passes the prism";
  const Vector3d strip_c = mid->point + 4 * mid->dir, strip_n = -mid->dir;
  const Vector3d across = Vector3d::UnitY().cross(strip_n).normalized();
  const double half_width = 0.015;

  // The mesh, 4 units tall, every triangle wound so that its front faces out of the prism (eta is
  // the index behind the front over the index in front).
  std::ostringstream obj;
  int vertices = 0;
  const Vector3d up(0, 2, 0), middle = (prism.v[0] + prism.v[1] + prism.v[2]) / 3;
  auto triangle = [&](Vector3d a, Vector3d b, Vector3d c) {
    if ((b - a).cross(c - a).dot(a - middle) < 0) std::swap(b, c);
    for (const Vector3d& p : {a, b, c})
      obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    obj << "f " << vertices + 1 << " " << vertices + 2 << " " << vertices + 3 << "\n";
    vertices += 3;
  };
  for (int k = 0; k < 3; ++k) {
    const Vector3d &a = prism.v[k], &b = prism.v[(k + 1) % 3];
    triangle(a - up, b - up, b + up);
    triangle(a - up, b + up, a + up);
  }
  triangle(prism.v[0] - up, prism.v[1] - up, prism.v[2] - up);
  triangle(prism.v[0] + up, prism.v[1] + up, prism.v[2] + up);
  write_file("prism.obj", obj.str());
  Vector3d corner = strip_c - half_width * across - 3 * Vector3d::UnitY();
  Vector3d u = 2 * half_width * across, v = 6 * Vector3d::UnitY();
  if (u.cross(v).dot(strip_n) < 0) std::swap(u, v);
  auto vec = [](const Vector3d& x) {
    std::ostringstream o;
    o << "[" << x.x() << ", " << x.y() << ", " << x.z() << "]";
    return o.str();
  };
  const std::string scene =
      write_file("prism.json", R"({"kasha_scene": 1,
  "wavelengths": {"min_nm": 400, "max_nm": 700, "bin_nm": 10},
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov_deg": 0.4, "width": 160, "height": 4},
  "materials": {"black": {}, "sf11": {"dielectric": {"eta": "SF11"}}},
  "shapes": [
    {"type": "obj", "file": "prism.obj", "material": "sf11"},
    {"type": "quad", "corner": )" + vec(corner) +
                                   R"(, "u": )" + vec(u) + R"(, "v": )" + vec(v) +
                                   R"(, "material": "black", "emission": 1}]})");
  // Eight independent passes: the centroid's standard error comes from their spread.
  const int passes = 8;
  RenderSettings s;
  s.passes = passes;
  s.integrator_settings.spp = 256;
  std::vector<std::vector<float>> running;  // the film's mean after each pass
  s.after_pass = [&](int, const Image& img) { running.push_back(img.spectral); };
  RenderResult r = render_scene(scene, s);
  ASSERT_EQ(running.size(), static_cast<size_t>(passes));
  const Scene& sc = r.scene;
  ASSERT_TRUE(sc.dispersive());
  const KCamera cam = sc.camera.to_kernel();
  const int N = sc.grid.bins, W = cam.width, H = cam.height;
  ASSERT_EQ(N, 30);

  std::vector<double> rendered(N), traced(N);
  int lit_bins = 0;
  double worst_error_bar = 0, mean_error_bar = 0;
  for (int i = 0; i < N; ++i) {
    // The traced centroid: 8 × 8 rays a pixel, each weighed by what the two faces transmit.
    const double eta = sc.materials[sc.material_index("sf11")].eta_bins[i];
    double tsum = 0, tweighted = 0;
    for (int py = 0; py < H; ++py)
      for (int px = 0; px < W; ++px)
        for (int sy = 0; sy < 8; ++sy)
          for (int sx = 0; sx < 8; ++sx) {
            double a = 2 * (px + (sx + 0.5) / 8) / W - 1, b = 1 - 2 * (py + (sy + 0.5) / 8) / H;
            Vector3d d;
            for (int k = 0; k < 3; ++k) d[k] = cam.forward[k] + a * cam.right[k] + b * cam.up[k];
            auto out = through(prism, Vector3d::Zero(), d.normalized(), eta);
            if (!out) continue;
            double t = (strip_c - out->point).dot(strip_n) / out->dir.dot(strip_n);
            if (t <= 0) continue;
            Vector3d hit = out->point + t * out->dir;
            if (std::abs((hit - strip_c).dot(across)) > half_width) continue;
            tsum += out->transmitted;
            tweighted += out->transmitted * px;
          }
    ASSERT_GT(tsum, 0) << "bin " << i << ": the traced strip is in view";
    traced[i] = tweighted / tsum;
    // The rendered centroid of each pass (pass k's image is k·mean_k − (k − 1)·mean_{k−1}).
    std::vector<double> c;
    for (int k = 0; k < passes; ++k) {
      double sum = 0, weighted = 0;
      for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
          size_t at = (static_cast<size_t>(py) * W + px) * N + i;
          double v =
              (k + 1) * double(running[k][at]) - (k > 0 ? k * double(running[k - 1][at]) : 0.0);
          sum += v;
          weighted += v * px;
        }
      if (sum > 0) c.push_back(weighted / sum);
    }
    ASSERT_GE(c.size(), 6u) << "bin " << i << ": the rendered strip is in view";
    double mean = 0, var = 0;
    for (double x : c) mean += x / c.size();
    for (double x : c) var += (x - mean) * (x - mean) / (c.size() - 1);
    const double error_bar = std::sqrt(var / c.size());
    worst_error_bar = std::max(worst_error_bar, error_bar);
    mean_error_bar += error_bar / N;
    rendered[i] = mean;
    ++lit_bins;
    EXPECT_LT(std::abs(rendered[i] - traced[i]), 4 * error_bar + 0.1)
        << "bin " << sc.grid.center(i) << " nm: " << rendered[i] << " ± " << error_bar << " vs "
        << traced[i];
  }
  // The test has the power to tell a bin from its neighbour (1.2 columns apart on average): the
  // error bars are smallest in the middle bins, where the film's importance sends most paths.
  EXPECT_LT(mean_error_bar, 0.3);
  EXPECT_LT(worst_error_bar, 1.0);
  EXPECT_EQ(lit_bins, N);
  std::printf("  error bars: mean %.2f, worst %.2f columns\n", mean_error_bar, worst_error_bar);
  std::printf("  strip column at 405 nm: %.2f (traced %.2f), at 695 nm: %.2f (traced %.2f)\n",
              rendered[0], traced[0], rendered[N - 1], traced[N - 1]);
  // Dispersion is there: blue and red land many columns apart (3.6° at this turn, 36 columns).
  EXPECT_GT(std::abs(traced[0] - traced[N - 1]), 20.0);
}

// A dispersive glass sphere (BK7) inside the fluorescent furnace leaves its uniform radiance as it
// is (a non-absorbing interface in a uniform, isotropic field, whatever its index): what this
// checks is the weight of the bin choice, w_j / p_j, on diagonal paths, on rank-1 paths (after a
// fluorescent bounce) and on photons — a bin chosen without its 1/p, or a rank-1 factor left
// unnormalized, moves the image off the analytic radiance. The directions are the prism's test.
TEST(Dispersion, ADispersiveSphereInTheFluorescentFurnaceLeavesItsRadiance) {
  const Furnace truth = analyze_furnace(load_scene(source_path("scenes/furnace_fluorescent.json")));
  ASSERT_TRUE(truth.qualifies) << truth.why_not;
  const std::string scene = write_file("furnace_bk7.json", R"({"kasha_scene": 1,
  "camera": {"position": [0.3, 0.2, -0.4], "look_at": [-1, 0.5, 1], "fov_deg": 60, "width": 24, "height": 24},
  "materials": {
    "brightened": {
      "passive": {"reflectance": {"nm": [380, 480, 560, 780], "value": [0.1, 0.3, 0.55, 0.6]}},
      "fluorescence": {"excitation": {"gaussian_nm": 430, "fwhm_nm": 70, "scale": 0.35},
                       "emission": {"gaussian_nm": 530, "fwhm_nm": 50}}},
    "bk7": {"dielectric": {"eta": "BK7"}}
  },
  "shapes": [
    {"type": "box", "min": [-1.5, -1, -1], "max": [1, 1.2, 2], "material": "brightened", "inward": true,
     "emission": {"csv": ")" + source_path("scenes/data/CIE_D65_300_780.csv") +
                                                               R"(", "scale": 0.01}},
    {"type": "sphere", "center": [-0.35, 0.35, 0.5], "radius": 0.4, "segments": 24, "material": "bk7"}
  ]})");
  // Backward on a spectral film, every bin within 4 standard errors. Photon mapping on
  // the XYZ film that users see: a path narrowed to a red bin at the glass carries the weight of
  // its rare choice, and photon mapping's pixels share photons, so per-bin error bars on a spectral
  // film are neither small nor trustworthy for it there; XYZ within 2 % after 16 passes.
  {
    RenderSettings s;
    s.integrator_settings.spp = 16;
    s.passes = 60;
    s.until = [&](int pass, const Image& img) {
      BinStats b = pixel_statistics(img, true);
      const double peak = *std::max_element(truth.radiance.begin(), truth.radiance.end());
      double worst = 0;
      for (size_t i = 0; i < truth.radiance.size(); ++i)
        if (truth.radiance[i] >= 1e-3 * peak)
          worst = std::max(worst, b.standard_error[i] / truth.radiance[i]);
      return pass >= 4 && worst < 0.003;
    };
    RenderResult r = render_scene(scene, s);
    ASSERT_TRUE(r.scene.dispersive());
    ASSERT_EQ(r.scene.grid.bins, static_cast<int>(truth.radiance.size()));
    // Every lit bin within 4 of its standard errors, which are at most 1 % (the red end, where
    // the film's importance sends few paths, has the widest).
    BinStats b = pixel_statistics(r.image, true);
    const double peak = *std::max_element(truth.radiance.begin(), truth.radiance.end());
    for (size_t i = 0; i < truth.radiance.size(); ++i) {
      const double t = truth.radiance[i];
      if (t < 1e-3 * peak) continue;
      EXPECT_LT(std::abs(b.mean[i] - t), 4 * b.standard_error[i] + 1e-6 * t)
          << "backward bin " << r.scene.grid.center(i) << " nm: " << b.mean[i] << " vs " << t;
      EXPECT_LT(b.standard_error[i], 0.015 * t) << "bin " << r.scene.grid.center(i) << " nm";
    }
    EXPECT_EQ(r.rejected, 0);
  }
  {
    RenderSettings s;
    s.integrator = "photon";
    s.spectral = false;
    s.integrator_settings.photons = 1 << 15;
    s.passes = 16;
    RenderResult r = render_scene(scene, s);
    const Image want = furnace_image(r.scene, truth.radiance, false);
    BinStats got = pixel_statistics(r.image, false), expected = pixel_statistics(want, false);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got.mean[k], expected.mean[k], 0.02 * expected.mean[k])
          << "photon, XYZ row " << k;
    EXPECT_EQ(r.rejected, 0);
  }
}

}  // namespace
