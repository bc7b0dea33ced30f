// A rough metal under a smooth coat (pbrt-v4's coatedconductor with a rough conductor;
// docs/materials.md#rough-coated-conductors): a sphere of it in a uniform sky, seen by an
// orthographic camera, shows the layer's albedo averaged over cosine-weighted directions — which
// the test finds by its own random walk through the layer, bounce by bounce, every bounce kept.
// The kernels sum three parts (the coat's mirror, the metal seen through the coat once, and a
// coated Lambert part for the rest), chosen per point; the sum must be the walk's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/error.h"
#include "material/ggx.h"
#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

constexpr double kEta = 1.5, kN = 0.2, kK = 3.0, kAlpha = 0.2236;

// Light arriving at cos θ = mu: the coat's reflection, then refraction in, and the metal's
// bounces, each leaving through the coat by 1 − F or coming back by F (1 beyond the escape cone).
double walk_albedo(double mu, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const HostGgx ggx{kAlpha};
  const double F = fresnel_reference(mu, {kEta, 0.0});
  double albedo = F, beta = 1 - F;
  const double s = std::sqrt(1 - mu * mu) / kEta;
  Eigen::Vector3d v(s, 0, std::sqrt(1 - s * s));
  while (beta > 1e-5) {
    const Eigen::Vector3d m = ggx.sample_visible(v, u(rng), u(rng));
    const Eigen::Vector3d r = -v + 2 * v.dot(m) * m;
    if (r.z() <= 0) break;
    beta *= ggx.g(v, r) / ggx.g1(v) * fresnel_reference(v.dot(m), {kN / kEta, kK / kEta});
    const double back = fresnel_reference(r.z(), {1 / kEta, 0.0});  // 1 under total reflection
    albedo += beta * (1 - back);
    beta *= back;
    v = Eigen::Vector3d(-r.x(), -r.y(), r.z());
  }
  return albedo;
}

double layer_albedo() {
  std::mt19937_64 rng(7);
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += walk_albedo(std::sqrt((i + 0.5) / n), rng);
  return sum / n;
}

// The sphere of `material` in the sky; no material: the sky alone.
std::string sphere_scene(const std::string& material) {
  std::string scene =
      "LookAt 0 0 5  0 0 0  0 1 0\n"
      "Camera \"orthographic\" \"float screenwindow\" [-1 1 -1 1]\n"
      "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 24\n"
      "WorldBegin\n"
      "LightSource \"infinite\" \"spectrum L\" [300 1 900 1]\n";
  // The sky alone still needs a shape (kasha refuses an empty scene): one behind the camera.
  if (material.empty()) scene += "Translate 0 0 20\n";
  scene += "Material " + (material.empty() ? "\"diffuse\"" : material) +
           "\nShape \"sphere\" \"float radius\" 1\n";
  return scene;
}

double image_mean(const std::string& name, const std::string& material,
                  const std::string& integrator, int passes) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = passes;
  s.grid = GridRequest{400, 700, 50};
  const RenderResult r = render_scene(write_file(name, sphere_scene(material)), s);
  const BinStats b = pixel_statistics(r.image, true);
  double mean = 0;
  for (double v : b.mean) mean += v / b.mean.size();
  return mean;
}

}  // namespace

TEST(LayeredMetal, ASphereInAUniformSkyShowsTheLayersWalk) {
  // The sky's share of the image: with the sphere black, against the sky alone.
  const double sky = image_mean("layered_sky.pbrt", "", "backward", 1);
  const double unlit =
      image_mean("layered_black.pbrt", "\"diffuse\" \"rgb reflectance\" [0 0 0]", "backward", 2) /
      sky;
  ASSERT_NEAR(unlit, 1 - M_PI / 4, 0.02);
  const std::string layered =
      "\"coatedconductor\" \"spectrum conductor.eta\" [300 0.2 900 0.2] "
      "\"spectrum conductor.k\" [300 3 900 3] \"float conductor.roughness\" 0.05 "
      "\"float thickness\" 0";
  const double truth = layer_albedo();
  for (const char* integrator : {"backward", "vcm"}) {
    const double mean = image_mean("layered_metal.pbrt", layered, integrator, 8);
    const double albedo = (mean / sky - unlit) / (1 - unlit);
    // The metal's one bounce alone (what a single-scattering model keeps) is 15 % darker.
    std::printf("%s: albedo %.5f, the walk's %.5f\n", integrator, albedo, truth);
    EXPECT_NEAR(albedo / truth, 1.0, 0.015) << integrator << ": " << albedo << " against " << truth;
  }
}

TEST(LayeredMetal, ARoughCoatOverAMetalIsRefused) {
  const std::string path =
      write_file("layered_rough_coat.pbrt",
                 sphere_scene("\"coatedconductor\" \"float interface.roughness\" 0.02"));
  try {
    render_scene(path, RenderSettings{});
    FAIL() << "a rough coat over a metal was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("layered_rough_coat.pbrt:6"), std::string::npos)
        << e.what();
  }
}
