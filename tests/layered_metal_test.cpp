// A rough layered metal (pbrt-v4's coatedconductor with a rough interface or conductor;
// docs/materials.md#rough-coated-conductors): a sphere of it in a uniform sky, seen by an
// orthographic camera, shows the layer's albedo averaged over cosine-weighted directions — which
// the test finds by its own random walk through the layer, bounce by bounce, every bounce kept
// (a smooth coat over rough metal; rough coats meet pbrt-v4's image in pbrt_reference_test.cpp).
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

// The image's mean over its bins and pixels, or over the pixels whose centres lie within
// `inside` of the sphere's centre (in the screen window's units: the sphere's radius is 1).
double image_mean(const std::string& name, const std::string& material,
                  const std::string& integrator, int passes, double inside = 0) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = passes;
  s.grid = GridRequest{400, 700, 50};
  const RenderResult r = render_scene(write_file(name, sphere_scene(material)), s);
  std::vector<size_t> pixels;
  for (int y = 0; inside > 0 && y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x)
      if (std::hypot((x + 0.5) / r.image.width * 2 - 1, (y + 0.5) / r.image.height * 2 - 1) <
          inside)
        pixels.push_back(static_cast<size_t>(y) * r.image.width + x);
  const BinStats b = pixel_statistics(r.image, true, pixels);
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

// The scene keeps the material as a mix of its two parts, each scaled by 1 / its share, and the
// walk's light split between them; a rough coat's lobe takes the walk's once-scattered share.
TEST(LayeredMetal, TheSceneSplitsItIntoTwoPartsChosenPerPoint) {
  const std::string path = write_file(
      "layered_parts.pbrt", sphere_scene("\"coatedconductor\" \"float interface.roughness\" 0.05 "
                                         "\"float conductor.roughness\" 0.01"));
  const Scene scene = load_scene(path);
  ASSERT_EQ(scene.materials.size(), 3u);
  const Material& mix = scene.materials[0];
  ASSERT_EQ(mix.kind, MaterialKind::mix);
  const Material& metal = scene.materials[mix.mix->materials[0]];
  const Material& layer = scene.materials[mix.mix->materials[1]];
  EXPECT_EQ(metal.kind, MaterialKind::conductor);
  EXPECT_TRUE(metal.under_coat);
  EXPECT_TRUE(metal.rough());
  ASSERT_TRUE(layer.coat.has_value());
  EXPECT_TRUE(layer.coat->rough());
  const double share = mix.mix->amount;
  EXPECT_GE(share, 0.1);
  EXPECT_LE(share, 0.9);
  EXPECT_NEAR(layer.layer_scale, 1 / share, 1e-12);
  // Copper's light after its first bounce: redder than what it reflects once, and some of it.
  ASSERT_FALSE(layer.rho.empty());
  EXPECT_GT(layer.rho.back(), layer.rho.front());
  EXPECT_GT(layer.rho.back(), 0.01);
  // Under a rough coat the once-scattered lobe gives up some of its light (0 < scale < 1).
  EXPECT_LT(metal.layer_scale * (1 - share), 1.0);
  EXPECT_GT(metal.layer_scale * (1 - share), 0.7);
}

// Every integrator sees one layered metal: a rough coat over rough gold (so light tracing sees
// the coat's reflection too) in the uniform sky, against backward's image, inside the sphere's
// silhouette (light tracing does not draw the sky seen directly; merging blurs the edge).
TEST(LayeredMetal, EveryIntegratorAgreesWithBackward) {
  const std::string gold =
      "\"coatedconductor\" \"spectrum conductor.eta\" \"metal-Au-eta\" \"spectrum conductor.k\" "
      "\"metal-Au-k\" \"float interface.roughness\" 0.05 \"float conductor.roughness\" 0.02";
  const double backward = image_mean("layered_gold.pbrt", gold, "backward", 8, 0.8);
  for (const char* integrator : {"bpt", "forward", "photon", "ppm", "vcm"})
    EXPECT_NEAR(image_mean("layered_gold.pbrt", gold, integrator, 8, 0.8) / backward, 1.0, 0.015)
        << integrator;
}
