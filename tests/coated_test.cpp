// Coated surfaces (kernels/materials/coat.h, docs/materials.md#coated-surfaces): a smooth dielectric coat over
// the seed model's Lambert parts, with every bounce between coat and base summed in closed form.
// - A white base under a clear coat (ρ = 1, no absorption) loses nothing: in a uniformly emitting
//   enclosure it shows exactly the enclosure, in every bin, through backward and photon mapping.
// - A coloured, fluorescent base under an absorbing coat shows the enclosure times its albedo
//   F(θo) + t(θo) τ̄ / η² · (I − R̄ B)⁻¹ B, computed here with the coat's integrals by quadrature
//   and a full N × N matrix inverse (not the kernels' Sherman–Morrison form).
// - Light tracing's connection through the coat to the camera against backward, under a lamp.
// - pbrt-v4's stochastic evaluation (LayeredBxDF::f, simulated here) is the same series cut after
//   five round trips in the coat: it agrees with the truncated sum, and the difference from
//   kasha's closed form is (ρ R̄)⁵ of the diffuse part.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <sstream>

#include "material/coat.h"
#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

double fresnel(double cos_i, double eta) { return fresnel_reference(cos_i, eta); }

// t(θ) = (1 − F(θ)) exp(−d / cos θt) for light from outside at cos θ.
double transmission(double mu, double eta, double d) {
  double s2 = (1 - mu * mu) / (eta * eta);
  if (s2 >= 1) return 0;
  return (1 - fresnel(mu, eta)) * std::exp(-d / std::sqrt(1 - s2));
}

// ∫₀¹ g(μ) 2μ dμ by the midpoint rule on a fine grid.
template <class G> double cosine_mean(G g) {
  const int n = 400000;
  double s = 0;
  for (int i = 0; i < n; ++i) {
    double mu = (i + 0.5) / n;
    s += g(mu) * 2 * mu;
  }
  return s / n;
}

struct Coat {
  double eta, d, internal, mean;  // R̄ and τ̄
};

Coat coat(double eta, double d) {
  Coat c{eta, d, 0, 0};
  c.internal = cosine_mean([&](double mu) { return fresnel(mu, 1 / eta) * std::exp(-2 * d / mu); });
  c.mean = cosine_mean([&](double mu) { return transmission(mu, eta, d); });
  return c;
}

// A camera 1° wide looking down at the floor (y = 0) at `deg` from its normal, inside an
// enclosure emitting a ramp over the spectrum (so fluorescence shows).
std::string floor_scene(const std::string& name, const std::string& material, double deg) {
  const double t = deg * M_PI / 180;
  std::ostringstream s;
  s << R"({"kasha_scene": 1,
  "camera": {"position": [0, 1, 0], "look_at": [)"
    << std::sin(t) << ", " << 1 - std::cos(t) << R"(, 0], "fov_deg": 1, "width": 8, "height": 8},
  "materials": {"black": {}, "floor": )"
    << material << R"(},
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 20, "material": "black", "inward": true,
     "emission": {"nm": [380, 780], "value": [2, 1]}},
    {"type": "quad", "corner": [-10, 0, -10], "u": [0, 0, 20], "v": [20, 0, 0], "material": "floor"}]})";
  return write_file(name, s.str());
}

// Every bin of the floor's radiance against `albedo` applied to the enclosure's radiance.
void expect_albedo(const std::string& scene, const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& albedo,
                   double tolerance, const std::string& label) {
  for (const char* integrator : {"backward", "photon"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.passes = 4;
    s.integrator_settings.spp = 64;
    s.integrator_settings.photons = 1 << 18;
    RenderResult r = render_scene(scene, s);
    const std::vector<double>& le = r.scene.emitters.front().per_bin;
    Eigen::VectorXd truth = albedo(Eigen::Map<const Eigen::VectorXd>(le.data(), le.size()));
    expect_bins_match(r, std::vector<double>(truth.data(), truth.data() + truth.size()), tolerance,
                      label + " " + integrator, IntegratorRegistry::find(integrator).traits.unbiased);
  }
}

TEST(Coated, AWhiteBaseUnderAClearCoatShowsTheFurnaceExactly) {
  const double deg = 60;
  const std::string scene = floor_scene(
      "coat_white.json", R"({"passive": {"reflectance": 1}, "coat": {"eta": 1.5, "thickness": 0}})", deg);
  expect_albedo(scene, [](const Eigen::VectorXd& le) { return le; }, 0.01, "white coat");
}

TEST(Coated, AFluorescentBaseUnderAnAbsorbingCoatKeepsItsAlbedo) {
  const double deg = 50, eta = 1.5, d = 0.05;
  const std::string scene = floor_scene("coat_fluorescent.json", R"({
    "passive": {"reflectance": {"nm": [380, 780], "value": [0.2, 0.7]}},
    "fluorescence": {"excitation": {"nm": [380, 460, 480, 780], "value": [0.6, 0.5, 0, 0]},
                     "emission": {"nm": [380, 480, 530, 600, 780], "value": [0, 0, 1, 0, 0]}},
    "coat": {"eta": 1.5, "thickness": 0.05}})",
                                        deg);
  Scene sc = load_scene(scene);
  const Material& m = sc.materials[sc.material_index("floor")];
  const int n = sc.grid.bins;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  for (int o = 0; o < n; ++o)
    for (int i = 0; i < n; ++i) B(o, i) = (o == i ? m.rho[o] : 0.0) + m.e_hat[o] * m.a[i];
  const Coat c = coat(eta, d);
  const Eigen::MatrixXd M = (Eigen::MatrixXd::Identity(n, n) - c.internal * B).inverse() * B;
  const double mu = std::cos(deg * M_PI / 180);
  const double specular = fresnel(mu, eta), diffuse = transmission(mu, eta, d) * c.mean / (eta * eta);
  std::printf("  coat η %g, d %g: R̄ %.5f, τ̄ %.5f; at %g°: F %.4f, diffuse factor %.4f\n", eta, d,
              c.internal, c.mean, deg, specular, diffuse);
  expect_albedo(
      scene, [&](const Eigen::VectorXd& le) -> Eigen::VectorXd { return specular * le + diffuse * (M * le); },
      0.02, "fluorescent coat");
}

// ---------------------------------------------------------------------------------------------
// Rough coats: pbrt-v4's GGX formulas written out again here (isotropic D, Smith Λ, unpolarized
// Fresnel), integrated over the sphere of directions on a (θ, φ) grid.

double ggx_d(double alpha, const Eigen::Vector3d& m) {
  if (m.z() <= 0) return 0;
  double c2 = m.z() * m.z(), t2 = (1 - c2) / c2, e = 1 + t2 / (alpha * alpha);
  return 1 / (M_PI * alpha * alpha * c2 * c2 * e * e);
}
double ggx_lambda(double alpha, const Eigen::Vector3d& w) {
  double c2 = w.z() * w.z(), t2 = std::max(0.0, 1 - c2) / c2;
  return (std::sqrt(1 + alpha * alpha * t2) - 1) / 2;
}

// The reflection lobe's albedo (E) and the transmittance as flux (T) of a rough interface of
// relative index eta seen at cos θ = mu from the side it is on.
void rough_albedos(double alpha, double eta, double mu, int nt, double& E, double& T) {
  const Eigen::Vector3d wo(std::sqrt(1 - mu * mu), 0, mu);
  const double lo = ggx_lambda(alpha, wo);
  const int np = nt / 4;
  E = T = 0;
  for (int i = 0; i < nt; ++i) {
    double t = M_PI * (i + 0.5) / nt, st = std::sin(t), ct = std::cos(t);
    for (int j = 0; j < np; ++j) {
      double p = M_PI * (j + 0.5) / np;
      Eigen::Vector3d wi(st * std::cos(p), st * std::sin(p), ct);
      double g = 1 / (1 + lo + ggx_lambda(alpha, wi)), dw = 2 * st * (M_PI / nt) * (M_PI / np);
      if (wi.z() > 0) {
        Eigen::Vector3d m = (wi + wo).normalized();
        E += ggx_d(alpha, m) * g * fresnel(wo.dot(m), eta) / (4 * wo.z()) * dw;
      } else {
        Eigen::Vector3d m = -(eta * wi + wo).normalized();
        if (m.z() <= 0 || wo.dot(m) <= 0 || wi.dot(m) >= 0) continue;
        double denom = wi.dot(m) + wo.dot(m) / eta;
        T += ggx_d(alpha, m) * (1 - fresnel(wo.dot(m), eta)) * g *
             std::abs(wi.dot(m) * wo.dot(m) / (denom * denom * wo.z())) * dw;
      }
    }
  }
}

TEST(Coated, ARoughFluorescentCoatKeepsItsSingleScatteringAlbedo) {
  const double deg = 50, eta = 1.5, d = 0.05, alpha = 0.5;  // roughness 0.25, remapped
  const std::string scene = floor_scene("coat_rough.json", R"({
    "passive": {"reflectance": {"nm": [380, 780], "value": [0.2, 0.7]}},
    "fluorescence": {"excitation": {"nm": [380, 460, 480, 780], "value": [0.6, 0.5, 0, 0]},
                     "emission": {"nm": [380, 480, 530, 600, 780], "value": [0, 0, 1, 0, 0]}},
    "coat": {"eta": 1.5, "thickness": 0.05, "roughness": 0.25}})",
                                        deg);
  Scene sc = load_scene(scene);
  const Material& m = sc.materials[sc.material_index("floor")];
  const int n = sc.grid.bins;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  for (int o = 0; o < n; ++o)
    for (int i = 0; i < n; ++i) B(o, i) = (o == i ? m.rho[o] : 0.0) + m.e_hat[o] * m.a[i];
  // t(μ) = T(μ) exp(−d / μt) and the inside lobe's albedo, by the midpoint rule in μ.
  auto layer_t = [&](double mu, int nt) {
    double E, T;
    rough_albedos(alpha, eta, mu, nt, E, T);
    return T * std::exp(-d / std::sqrt(1 - (1 - mu * mu) / (eta * eta)));
  };
  const int nm = 48;
  double mean = 0, internal = 0;
  for (int k = 0; k < nm; ++k) {
    double mu = (k + 0.5) / nm, E, T;
    mean += layer_t(mu, 400) * 2 * mu / nm;
    rough_albedos(alpha, 1 / eta, mu, 400, E, T);
    internal += E * std::exp(-2 * d / mu) * 2 * mu / nm;
  }
  const double mu_o = std::cos(deg * M_PI / 180);
  double specular, T_o;
  rough_albedos(alpha, eta, mu_o, 1600, specular, T_o);
  const double diffuse = layer_t(mu_o, 1600) * mean / (eta * eta);
  const Eigen::MatrixXd M = (Eigen::MatrixXd::Identity(n, n) - internal * B).inverse() * B;
  std::printf("  rough coat α %g: R̄ %.4f, τ̄ %.4f; at %g°: E %.4f, diffuse factor %.4f\n", alpha, internal,
              mean, deg, specular, diffuse);
  expect_albedo(
      scene, [&](const Eigen::VectorXd& le) -> Eigen::VectorXd { return specular * le + diffuse * (M * le); },
      0.02, "rough coat");
}

// A barely rough coat's tables (host/material/coat.h) approach the smooth coat's closed form.
TEST(Coated, ANearlySmoothRoughCoatApproachesTheSmoothOne) {
  CoatDesc c;
  c.eta = 1.5;
  c.thickness = 0.02;
  c.alpha = 0.01;
  const CoatTables t = rough_coat_tables(c);
  const Coat smooth = coat(1.5, 0.02);
  for (int k = 16; k < kCoatTableSize; k += 8) {  // μ ≥ 0.25: grazing, even α 0.01 masks a little
    const double mu = static_cast<double>(k) / (kCoatTableSize - 1);
    EXPECT_NEAR(t.reflect[k], fresnel(mu, 1.5), 0.005) << "E at μ " << mu;
    EXPECT_NEAR(t.transmit[k], transmission(mu, 1.5, 0.02), 0.005) << "t at μ " << mu;
  }
  EXPECT_NEAR(t.internal, smooth.internal, 0.01);
  EXPECT_NEAR(t.mean, smooth.mean, 0.01);
}

// Light tracing connects each photon hit on a coated floor to the camera through t(θi) t(θo) / η²
// (and, on the rough coat, through its GGX lobe); backward samples the coat. Light tracing cannot see the coat's mirror reflection (a delta lobe),
// so nothing lit may show in it: the lamp hangs above and behind the camera, where its mirror
// image falls beyond the floor's edge, and the floor sees only black around it. Region by region
// within 4 standard errors of their difference.
TEST(Coated, LightTracingAgreesWithBackwardThroughTheCoat) {
  const std::string scene = write_file("coat_pair.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 1.2, 1.6], "look_at": [0, 0.2, 0], "fov_deg": 55, "width": 24, "height": 24},
  "materials": {"black": {},
                "lacquer": {"passive": {"reflectance": {"nm": [380, 780], "value": [0.3, 0.8]}},
                            "fluorescence": {"excitation": {"nm": [380, 500, 520, 780], "value": [0.5, 0.4, 0, 0]},
                                             "emission": {"nm": [380, 520, 560, 620, 780], "value": [0, 0, 1, 0, 0]}},
                            "coat": {"eta": 1.5, "thickness": 0.02}},
                "grey": {"passive": {"reflectance": 0.5}, "coat": {"eta": 1.3, "thickness": 0, "roughness": 0.05}}},
  "shapes": [
    {"type": "quad", "corner": [-1, 0, -1], "u": [0, 0, 2], "v": [1, 0, 0], "material": "lacquer"},
    {"type": "quad", "corner": [0, 0, -1], "u": [0, 0, 2], "v": [1, 0, 0], "material": "grey"},
    {"type": "quad", "corner": [-0.3, 1.5, 1.1], "u": [0.6, 0, 0], "v": [0, 0, 0.6], "material": "black",
     "emission": {"blackbody_K": 4000, "scale": 1e-6}}]})");
  RenderSettings b;
  b.spectral = false;
  b.passes = 4;
  b.integrator_settings.spp = 64;
  RenderResult backward = render_scene(scene, b);
  RenderSettings f = b;
  f.integrator = "forward";
  f.integrator_settings.photons = 1 << 19;
  RenderResult forward = render_scene(scene, f);
  std::map<std::string, std::vector<size_t>> regions =
      primary_hit_regions(forward.scene, forward.scene.camera);
  ASSERT_GE(regions["lacquer"].size(), 100u);
  ASSERT_GE(regions["grey"].size(), 100u);
  for (const auto& [name, pixels] : regions) {
    BinStats t = pixel_statistics(forward.image, false, pixels);
    BinStats d = difference_statistics(forward.image, backward.image, false, pixels);
    for (int k = 0; k < 3; ++k) {
      std::printf("  %-8s row %d: forward/backward - 1 = %+.2f %% (± %.2f %%)\n", name.c_str(), k,
                  100 * d.mean[k] / (t.mean[k] - d.mean[k]),
                  100 * d.standard_error[k] / (t.mean[k] - d.mean[k]));
      EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << name << " row " << k;
    }
  }
}

// Photon mapping stores t(θi) Φ at a coated surface and gives the visible point t(θo) / η²: a
// coated floor lit mostly by a white wall under a rough coat (indirect light, from the photon map,
// photons scattered by the coat's lobe among them) against backward,
// region by region within 3 % (photon mapping's bias from its radius is below that here).
TEST(Coated, PhotonMappingAgreesWithBackwardOnIndirectLightThroughTheCoat) {
  const std::string scene = write_file("coat_indirect.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 1.2, 1.6], "look_at": [0, 0.2, 0], "fov_deg": 55, "width": 24, "height": 24},
  "materials": {"black": {}, "white": {"passive": {"reflectance": 0.9}, "coat": {"roughness": 0.05}},
                "lacquer": {"passive": {"reflectance": {"nm": [380, 780], "value": [0.3, 0.8]}},
                            "fluorescence": {"excitation": {"nm": [380, 500, 520, 780], "value": [0.5, 0.4, 0, 0]},
                                             "emission": {"nm": [380, 520, 560, 620, 780], "value": [0, 0, 1, 0, 0]}},
                            "coat": {"eta": 1.5, "thickness": 0.02}}},
  "shapes": [
    {"type": "quad", "corner": [-1, 0, -1], "u": [0, 0, 2], "v": [2, 0, 0], "material": "lacquer"},
    {"type": "quad", "corner": [-1, 0, -1], "u": [2, 0, 0], "v": [0, 1.5, 0], "material": "white"},
    {"type": "quad", "corner": [-0.5, 1.2, -0.2], "u": [1, 0, 0], "v": [0, -0.3, -0.5], "material": "black",
     "emission": {"blackbody_K": 4000, "scale": 1e-6}}]})");
  RenderSettings b;
  b.spectral = false;
  b.passes = 4;
  b.integrator_settings.spp = 64;
  RenderResult backward = render_scene(scene, b);
  RenderSettings p = b;
  p.integrator = "photon";
  p.passes = 16;
  p.integrator_settings.spp = 16;
  p.integrator_settings.photons = 1 << 17;
  RenderResult photon = render_scene(scene, p);
  std::map<std::string, std::vector<size_t>> regions = primary_hit_regions(photon.scene, photon.scene.camera);
  ASSERT_GE(regions["lacquer"].size(), 100u);
  for (const auto& [name, pixels] : regions) {
    if (name == "lamp") continue;
    BinStats t = pixel_statistics(photon.image, false, pixels);
    BinStats d = difference_statistics(photon.image, backward.image, false, pixels);
    for (int k = 0; k < 3; ++k) {
      const double b = t.mean[k] - d.mean[k];
      std::printf("  %-8s row %d: photon/backward - 1 = %+.2f %% (± %.2f %%)\n", name.c_str(), k,
                  100 * d.mean[k] / b, 100 * d.standard_error[k] / b);
      EXPECT_LT(std::abs(d.mean[k]), 0.03 * b) << name << " row " << k;
    }
  }
}

// pbrt-v4's LayeredBxDF::f for coateddiffuse (smooth top, diffuse bottom ρ, albedo 0, maxdepth
// 10), written out for one wavelength: transmission in along wo, then per depth a crossing of the
// layer (Tr), at the base its next-event term towards the presampled wis and a cosine-sampled
// reflection, at the top a reflection by F; Russian roulette after depth 3 when β < 0.25.
double pbrt_layered_f(double mu_o, double mu_i, double rho, const Coat& c, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  auto tr = [&](double mu) { return c.d > 0 ? std::exp(-c.d / mu) : 1.0; };
  auto inside = [&](double mu) { return std::sqrt(1 - (1 - mu * mu) / (c.eta * c.eta)); };
  // wos: transmission from wo in radiance mode (1 − F)/η²; wis: from wi in importance mode (1 − F).
  double beta = (1 - fresnel(mu_o, c.eta)) / (c.eta * c.eta);
  const double wis = 1 - fresnel(mu_i, c.eta), mu_wis = inside(mu_i);
  double w = inside(mu_o), f = 0;
  bool at_top = true;
  for (int depth = 0; depth < 10; ++depth) {
    if (depth > 3 && beta < 0.25) {
      double q = std::max(0.0, 1 - beta);
      if (u(rng) < q) break;
      beta /= 1 - q;
    }
    at_top = !at_top;
    beta *= tr(w);
    if (at_top) {
      beta *= fresnel(w, 1 / c.eta);  // reflection sampled alone: weight F (1 under TIR)
    } else {
      f += beta * rho / M_PI * tr(mu_wis) * wis;
      beta *= rho;
      w = std::sqrt(u(rng));  // cosine-sampled
    }
  }
  return f;
}

TEST(Coated, PbrtV4sStochasticEvaluationIsTheSeriesCutAfterFiveRoundTrips) {
  const Coat c = coat(1.5, 0.01);
  std::mt19937_64 rng(7);
  const double mu_o = std::cos(30 * M_PI / 180), mu_i = std::cos(45 * M_PI / 180);
  for (double rho : {0.5, 0.9}) {
    const int n = 2000000;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
      double f = pbrt_layered_f(mu_o, mu_i, rho, c, rng);
      sum += f;
      sum2 += f * f;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    const double first = transmission(mu_o, c.eta, c.d) * transmission(mu_i, c.eta, c.d) * rho /
                         (M_PI * c.eta * c.eta);
    const double x = rho * c.internal, closed = first / (1 - x), cut = first * (1 - std::pow(x, 5)) / (1 - x);
    std::printf("  ρ %.1f: pbrt-v4 %.6f ± %.6f, five round trips %.6f, kasha %.6f: pbrt-v4 %.2f %% lower\n",
                rho, mean, se, cut, closed, 100 * (1 - mean / closed));
    EXPECT_LT(std::abs(mean - cut), 4 * se) << "rho " << rho;
    EXPECT_GT(closed - mean, 4 * se) << "rho " << rho << ": the cut is visible";
  }
}

}  // namespace
