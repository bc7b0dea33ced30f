// Sphere lights (kernels/lights/sphere_light.h): next-event estimation of an emitting sphere by the
// solid angle of its circumscribed sphere. Its irradiance against the analytic L·π·(r/d)²·cos α
// and the tessellation's own, the share of directions that land on the mesh against what the
// tessellation predicts, its density against light_pdf_from; which shapes are sphere lights; and
// every integrator with next-event estimation against the same mesh sampled triangle by triangle.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "chi2.h"
#include "kernel_harness.h"
#include "light_sample_kernel.h"
#include "render/device_scene.h"
#include "render_support.h"
#include "scene/scene.h"
#include "scene/shape_mesh.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

// Work item i: next-event estimation at x (normal +z) with u[2i], u[2i+1]: the irradiance sample
// L cos / pdf (0 where it failed), whether it landed, and its density against light_pdf_from at
// the triangle the direction to the point hits first.
const std::string kNeeSource = std::string(kLightSampleKernelHead) + R"(
__kernel void nee(KASHA_SCENE_PARAMS, __global const float* x_in, __global const float* u,
                  __global float* out) {
  SAMPLE_LIGHT_AT_X_IN();
  __global float* o = out + 4 * i;
  o[0] = o[1] = o[2] = o[3] = 0.0f;
  if (!(pdf > 0.0f)) return;
  float3 to = p.position - x;
  float3 wi = normalize(to);
  HitPoint h;
  float from = -1.0f;
  if (intersect_scene(&s, x, wi, &h)) from = light_pdf_from(&s, h.tri, x, h.x, dot(h.n, -wi));
  o[0] = emitter_spectrum(&s, p.emitter)[0] * fmax(0.0f, wi.z) / pdf;
  o[1] = 1.0f;
  o[2] = pdf;
  o[3] = from;
}
)";

// Lambert's projected solid angle (about +z) and the solid angle of triangle t seen from x.
void triangle_angles(const Vector3d& x, const Triangle& t, double& projected, double& solid) {
  Vector3d v[3];
  for (int k = 0; k < 3; ++k) v[k] = (t[k] - x).normalized();
  projected = 0;
  for (int k = 0; k < 3; ++k) {
    const Vector3d a = v[k], b = v[(k + 1) % 3], c = a.cross(b);
    projected += std::atan2(c.norm(), a.dot(b)) * c.normalized().z();
  }
  projected = std::abs(projected) / 2;
  solid = 2 * std::atan2(std::abs(v[0].dot(v[1].cross(v[2]))),
                         1 + v[0].dot(v[1]) + v[0].dot(v[2]) + v[1].dot(v[2]));
}

std::string sphere_scene(const std::string& name, const Vector3d& c, double r, int segments) {
  std::ostringstream s;
  s << R"({"kasha_scene": 1, "wavelengths": {"min_nm": 500, "max_nm": 600, "bin_nm": 25},
  "camera": {"position": [0, -3, 1], "look_at": [0, 0, 0], "fov_deg": 40, "width": 8, "height": 8},
  "materials": {"black": {}},
  "shapes": [{"type": "sphere", "center": [)"
    << c.x() << ", " << c.y() << ", " << c.z() << "], \"radius\": " << r
    << ", \"segments\": " << segments << R"(, "material": "black", "emission": 1}]})";
  return write_file(name, s.str());
}

// Irradiance at x (normal +z) from a sphere lamp of radiance 1, by next-event estimation.
void check_irradiance(const std::string& label, const Vector3d& x, const Vector3d& c, double r) {
  constexpr size_t kSamples = 200000;
  constexpr int kSegments = 24;
  const Scene scene = load_scene(sphere_scene(label + ".json", c, r, kSegments));
  ASSERT_TRUE(scene.shapes[0].sphere_light);
  DeviceScene device(test_device(), scene);
  const KernelSceneData& data = device.data();
  ASSERT_FALSE(data.light_spheres.empty());
  TestKernel kernel(kNeeSource, "sphere_nee_test.cl", "nee", scene_defines(scene, false));
  device.bind(kernel.handle(), 0, kSamples);
  kernel.input(3, std::vector<float>{float(x.x()), float(x.y()), float(x.z())});
  const std::vector<float> out = kernel.sample(4, uniforms(2 * kSamples, 3), 5, 4, kSamples);

  // The tessellation as the kernels have it: its triangles' projected solid angles (the
  // irradiance from radiance 1) and solid angles (the directions that land), front sides only.
  double mesh_e = 0, mesh_omega = 0;
  for (const KTriangle& t : data.bvh.triangles) {
    const Triangle tri = {Vector3d(t.v0[0], t.v0[1], t.v0[2]), Vector3d(t.v1[0], t.v1[1], t.v1[2]),
                          Vector3d(t.v2[0], t.v2[1], t.v2[2])};
    const Vector3d n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    if (!(n.norm() > 0) || n.dot(x - tri[0]) <= 0) continue;
    double projected, solid;
    triangle_angles(x, tri, projected, solid);
    mesh_e += projected, mesh_omega += solid;
  }
  const KSphereLight& l = data.light_spheres[0];
  const Vector3d cf(l.centre[0], l.centre[1], l.centre[2]);
  const double cone =
      2 * M_PI * (1 - std::sqrt(1 - l.radius * double(l.radius) / (cf - x).squaredNorm()));
  const double d = (c - x).norm(), analytic = M_PI * r * r / (d * d) * (c - x).normalized().z();

  double sum = 0, sum2 = 0, landed = 0, worst_pdf = 0;
  int bad = 0;
  for (size_t i = 0; i < kSamples; ++i) {
    const float* o = &out[4 * i];
    sum += o[0], sum2 += double(o[0]) * o[0], landed += o[1];
    if (o[1] > 0) {
      // The direction to a point on an edge may meet the neighbour, seen edge on: a few in 10⁵.
      const double err = std::abs(o[3] - o[2]) / o[2];
      if (err < 1) worst_pdf = std::max(worst_pdf, err);
      if (err > 1e-4) ++bad;
    }
  }
  const double mean = sum / kSamples, se = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
  const double share = landed / kSamples, predicted = mesh_omega / cone;
  std::printf(
      "[ sphere   ] %s: irradiance %.6g ± %.2g, the mesh's %.6g, the sphere's %.6g; %.4f of the "
      "directions land, the mesh predicts %.4f; pdf against light_pdf_from within %.2g, %d off\n",
      label.c_str(), mean, se, mesh_e, analytic, share, predicted, worst_pdf, bad);
  EXPECT_LT(std::abs(mean - mesh_e), 4 * se + 1e-4 * mesh_e) << label;
  EXPECT_LT(se, 2e-3 * mesh_e) << label;             // the test can tell
  EXPECT_NEAR(mesh_e / analytic, 1, 0.02) << label;  // the tessellation is the sphere's
  EXPECT_LT(std::abs(share - predicted), 4 * std::sqrt(predicted * (1 - predicted) / kSamples))
      << label;
  EXPECT_LT(worst_pdf, 1e-4) << label;
  EXPECT_LT(bad, 10) << label;
}

}  // namespace

TEST(SphereLight, IrradianceIsTheProjectedSolidAngle) {
  check_irradiance("near", Vector3d(0.1, -0.2, 0), Vector3d(0.4, 0.3, 1.2), 0.5);
  check_irradiance("far", Vector3d(0.1, -0.2, 0), Vector3d(10, -6, 40), 0.3);
}

namespace {

// A pbrt-v4 scene of one emitting sphere under `placed` (transform lines) with `params`.
Scene pbrt_sphere(const std::string& name, const std::string& placed, const std::string& params) {
  const std::string text =
      "LookAt 0 1 3  0 1 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\n"
      "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
      "AttributeBegin\n" +
      placed + "\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nShape \"sphere\" " + params +
      "\nAttributeEnd\n";
  return load_scene(write_file(name, text));
}

}  // namespace

TEST(SphereLight, OnlyWholeOutwardSpheresUnderASimilarityAreOne) {
  const Scene whole = pbrt_sphere("whole.pbrt", "Translate 1 2 3 Rotate 30 1 1 0 Scale 2 2 2",
                                  "\"float radius\" 0.5");
  ASSERT_TRUE(whole.shapes[0].sphere_light);
  EXPECT_LT((whole.shapes[0].sphere_light->centre - Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_NEAR(whole.shapes[0].sphere_light->radius, 1.0, 1e-12);
  EXPECT_FALSE(pbrt_sphere("stretched.pbrt", "Scale 1 2 1", "").shapes[0].sphere_light);
  EXPECT_FALSE(pbrt_sphere("cut.pbrt", "", "\"float zmax\" 0.5").shapes[0].sphere_light);
  EXPECT_FALSE(pbrt_sphere("wedge.pbrt", "", "\"float phimax\" 180").shapes[0].sphere_light);
  EXPECT_FALSE(pbrt_sphere("inside.pbrt", "ReverseOrientation", "").shapes[0].sphere_light);
  const std::string json = R"({"kasha_scene": 1,
  "camera": {"position": [0, -3, 1], "look_at": [0, 0, 0], "fov_deg": 40, "width": 8, "height": 8},
  "materials": {"black": {}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "black", "emission": 1},
             {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "black", "emission": 1, "inward": true},
             {"type": "sphere", "center": [6, 0, 0], "radius": 1, "material": "black"}]})";
  const Scene kasha = load_scene(write_file("spheres.json", json));
  EXPECT_TRUE(kasha.shapes[0].sphere_light);
  EXPECT_FALSE(kasha.shapes[1].sphere_light);  // seen from inside
  EXPECT_FALSE(kasha.shapes[2].sphere_light);  // emits nothing
  EXPECT_EQ(scene_defines(kasha, false).at("KASHA_SPHERE_LIGHTS"), "1");
}

namespace {

// A lamp over a floor by a wall: the lamp a "sphere" (a sphere light), or the same triangles
// given as "triangles" (sampled triangle by triangle, as before sphere lights).
std::string lamp_scene(const std::string& name, bool sphere_light) {
  const Vector3d c(0.1, 0.45, 0.2);
  const double r = 0.2;
  const int segments = 16;
  std::ostringstream lamp;
  if (sphere_light) {
    lamp << R"({"type": "sphere", "center": [)" << c.x() << ", " << c.y() << ", " << c.z()
         << "], \"radius\": " << r << ", \"segments\": " << segments;
  } else {
    const ShapeMesh mesh = sphere_triangles(c, r, segments);
    lamp.precision(17);
    lamp << R"({"type": "triangles", "positions": [)";
    std::string sep;
    for (const Triangle& t : mesh.tris)
      for (const Vector3d& v : t)
        lamp << sep << v.x() << ", " << v.y() << ", " << v.z(), sep = ", ";
    lamp << R"(], "indices": [)";
    for (size_t i = 0; i < 3 * mesh.tris.size(); ++i) lamp << (i ? ", " : "") << i;
    lamp << "]";
  }
  lamp << R"(, "material": "lamp", "emission": 4})";
  return write_file(
      name, R"({"kasha_scene": 1, "wavelengths": {"min_nm": 400, "max_nm": 700, "bin_nm": 100},
  "camera": {"position": [0, 1.1, 1.6], "look_at": [0, 0.2, 0], "fov_deg": 60, "width": 20, "height": 20},
  "materials": {"grey": {"passive": {"reflectance": 0.6}}, "lamp": {"passive": {"reflectance": 0.2}},
                "gloss": {"passive": {"reflectance": 0.2}, "gloss": {"reflectance": 0.3, "cone_deg": 15}}},
  "shapes": [{"type": "quad", "corner": [-1, 0, 1], "u": [2, 0, 0], "v": [0, 0, -2], "material": "gloss"},
             {"type": "quad", "corner": [-1, 0, -0.6], "u": [2, 0, 0], "v": [0, 1.5, 0], "material": "grey"},
             )" +
                lamp.str() + "]}");
}

}  // namespace

// Each integrator with next-event estimation renders the same image, in the mean, whether the
// lamp is a sphere light or its triangles are sampled one by one.
TEST(SphereLight, EveryIntegratorAgreesWithTriangleSampling) {
  const std::string as_sphere = lamp_scene("sphere.json", true);
  const std::string as_mesh = lamp_scene("mesh.json", false);
  EXPECT_EQ(scene_defines(load_scene(as_sphere), false).at("KASHA_SPHERE_LIGHTS"), "1");
  EXPECT_EQ(scene_defines(load_scene(as_mesh), false).at("KASHA_SPHERE_LIGHTS"), "0");
  for (const char* integrator : {"backward", "vcm", "bpt", "photon"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.spectral = false;
    s.passes = 8;
    const RenderResult a = render_scene(as_sphere, s);
    s.integrator_settings.seed = 7;
    const RenderResult b = render_scene(as_mesh, s);
    const BinStats t = pixel_statistics(a.image, false);
    const BinStats d = difference_statistics(a.image, b.image, false);
    for (int k = 0; k < 3; ++k) {
      std::printf("[ agree    ] %-8s row %d: sphere light / triangles - 1 = %+.2f %% (± %.2f %%)\n",
                  integrator, k, 100 * d.mean[k] / (t.mean[k] - d.mean[k]),
                  100 * d.standard_error[k] / (t.mean[k] - d.mean[k]));
      EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << integrator << " row " << k;
      EXPECT_LT(d.standard_error[k], 0.01 * t.mean[k]) << integrator;  // tight enough to tell
    }
  }
}

namespace {

// bpt restricted to paths of `length` segments in a grey box lit by a sphere lamp, MIS-weighted
// or plain (emission hits alone, unweighted: vcm_test.cpp's reference).
Image box_length(int length, int passes, bool plain) {
  const std::string scene = write_file("sphere_box.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, -0.2, 0.9], "look_at": [0, 0.1, -1], "fov_deg": 70, "width": 32, "height": 32},
    "materials": {"grey": {"passive": {"reflectance": 0.5}},
                  "yellow": {"passive": {"reflectance": {"nm": [380, 500, 560, 780], "value": [0.05, 0.1, 0.7, 0.8]}}},
                  "lamp": {"passive": {"reflectance": 0.2}}},
    "shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "grey", "inward": true},
               {"type": "box", "min": [-0.5, -1, -0.6], "max": [0.1, -0.4, 0.0], "material": "yellow"},
               {"type": "sphere", "center": [0.2, 0.5, -0.3], "radius": 0.3, "segments": 24,
                "material": "lamp", "emission": {"blackbody_K": 5000, "scale": 1e-5}}]})");
  RenderSettings s;
  s.integrator = "bpt";
  s.passes = passes;
  s.spectral = false;
  s.hooks.vcm_length = length;
  s.hooks.vcm_emission_only = plain;
  s.hooks.vcm_no_seen_light = plain;
  return render_scene(scene, s).image;
}

}  // namespace

// The weights of every path sum to one with a sphere light: bpt's techniques together (next-event
// estimation by the sphere's cone, emission hits weighed by its density, light tracing and
// connections, whose weights take it at the light subpath's first vertex) against emission hits
// alone, for direct light (2 segments) and one bounce (3). light_pdf_from doubled for sphere
// lights was measured to fail it by 14 and 23 standard errors.
TEST(SphereLight, BptWeightsSumToOneWithASphereLight) {
  for (int length : {2, 3}) {
    const Image weighted = box_length(length, 16, false), plain = box_length(length, 128, true);
    // Pixel by pixel, so the image's structure cancels (the two renders are independent).
    const BinStats b = pixel_statistics(plain, false),
                   d = difference_statistics(weighted, plain, false);
    for (int k = 0; k < 3; ++k) {
      const double z = d.mean[k] / d.standard_error[k];
      std::printf(
          "[ weights  ] length %d row %d: weighted / plain - 1 = %+.2f %% (%+.1f standard "
          "errors)\n",
          length, k, 100 * d.mean[k] / b.mean[k], z);
      EXPECT_LT(std::abs(z), 4.0) << "length " << length << " row " << k;
      EXPECT_LT(d.standard_error[k], 0.01 * b.mean[k]);  // it can tell
    }
  }
}
