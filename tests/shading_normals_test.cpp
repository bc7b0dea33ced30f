// Shading normals (OBJ `vn`, kernels/geometry/hit_point.h, docs/formats.md#shading-normals):
// - A floor whose shading normal leans 20° towards a distant light shows ρ/π·E·cos 25° (the
//   light's angle to the shading normal, not the 45° to the geometric one) in every integrator:
//   camera paths evaluate the surface about the shading normal; light tracing needs Veach's
//   correction |wi·ns| / |wi·ng| for it (without it, it shows cos 45°).
// - No light leaks: a lamp under a floor whose shading normal leans 60° leaves everything above
//   the floor black in every integrator (a Lambert bounce about the shading normal alone would
//   carry light through).
// - Smooth-shaded low-poly spheres (a Lambert one, a rough gold one) on a floor under a lamp:
//   light tracing against backward region by region within 4 standard errors, photon mapping (the
//   spheres' light on the floor goes through the photon map with the correction) within 3 %.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// The square −2 ≤ x, y ≤ 2 at z = 0, facing +z, with every vertex's shading normal leaning `deg`
// from +z towards +x.
std::string tilted_floor(const std::string& name, double deg) {
  const double t = deg * M_PI / 180;
  std::ostringstream s;
  s << "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nvn " << std::sin(t) << " 0 " << std::cos(t)
    << "\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
  return write_file(name, s.str());
}

std::string floor_scene(const std::string& name, const std::string& obj, const std::string& from,
                        const std::string& material = R"({"passive": {"reflectance": 0.5}})") {
  return write_file(name, R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 30, "width": 16, "height": 16},
  "materials": {"grey": )" + material + R"(},
  "shapes": [{"type": "obj", "file": ")" + obj + R"(", "material": "grey"}],
  "lights": [{"type": "distant", "from": )" + from + R"(, "to": [0, 0, 0],
              "irradiance": {"nm": [380, 780], "value": [1, 2]}}]})");
}

RenderResult render(const std::string& scene, const std::string& integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.passes = 4;
  s.integrator_settings.spp = 16;
  s.integrator_settings.photons = 1 << 19;
  return render_scene(scene, s);
}

TEST(ShadingNormals, AFloorIsLitAsItsShadingNormalFacesTheLight) {
  const std::string obj = tilted_floor("tilted_floor.obj", 20);
  const std::string scene = floor_scene("tilted_floor.json", obj, "[1, 0, 1]");
  for (const char* integrator : {"backward", "photon", "forward", "vcm"}) {
    RenderResult r = render(scene, integrator);
    ASSERT_TRUE(r.scene.shading_normals());
    const std::vector<double>& e = r.scene.lights.front().per_bin;
    std::vector<double> truth(e.size());
    for (size_t i = 0; i < e.size(); ++i) truth[i] = 0.5 / M_PI * e[i] * std::cos(25 * M_PI / 180);
    expect_bins_match(r, truth, 0.02, std::string("tilted floor ") + integrator,
                      IntegratorRegistry::find(integrator).traits.unbiased);
  }
}

// A rough gold floor under the same tilted shading normal: light tracing's connection through a
// rough surface takes the geometric cosine towards the camera and the arrival correction too, and
// agrees with backward (about 30 % apart without them).
TEST(ShadingNormals, LightTracingAgreesWithBackwardOnRoughMetalUnderATiltedShadingNormal) {
  const std::string obj = tilted_floor("tilted_gold.obj", 20);
  const std::string scene =
      floor_scene("tilted_gold.json", obj, "[1, 0, 1]", R"({"conductor": {"metal": "Au", "roughness": 0.3}})");
  RenderSettings b;
  b.spectral = false;
  b.passes = 4;
  b.integrator_settings.spp = 16;
  RenderResult backward = render_scene(scene, b);
  RenderSettings f = b;
  f.integrator = "forward";
  f.integrator_settings.photons = 1 << 19;
  RenderResult forward = render_scene(scene, f);
  BinStats t = pixel_statistics(forward.image, false);
  BinStats d = difference_statistics(forward.image, backward.image, false);
  for (int k = 0; k < 3; ++k) {
    const double ref = t.mean[k] - d.mean[k];
    std::printf("  rough gold row %d: forward/backward - 1 = %+.2f %% (± %.2f %%)\n", k, 100 * d.mean[k] / ref,
                100 * d.standard_error[k] / ref);
    EXPECT_GT(ref, 0) << "row " << k;
    EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << "row " << k;
  }
}

TEST(ShadingNormals, NoLightLeaksThroughTheSurface) {
  // A lamp under the floor lights its underside; above it stands a white wall the camera sees.
  // The shading normal leans 60°, so a Lambert bounce about it (on either side) would send light
  // through the floor: from the lamp up to the wall, or from the wall down to the lamp. With the
  // geometric side kept, nothing above the floor is lit.
  const std::string obj = tilted_floor("leaky_floor.obj", 60);
  const std::string scene = write_file("leaky_floor.json", R"({"kasha_scene": 1,
  "camera": {"position": [1.5, 0, 2], "look_at": [-1.5, 0, 0.4], "fov_deg": 40, "width": 16, "height": 16},
  "materials": {"black": {}, "white": {"passive": {"reflectance": 0.9}}},
  "shapes": [{"type": "obj", "file": ")" + obj + R"(", "material": "white"},
             {"type": "quad", "corner": [-1.5, -2, 0], "u": [0, 4, 0], "v": [0, 0, 1.5], "material": "white"},
             {"type": "quad", "corner": [-0.5, -0.5, -0.3], "u": [1, 0, 0], "v": [0, 1, 0], "material": "black",
              "emission": 10}]})");
  for (const char* integrator : {"backward", "photon", "forward", "vcm"}) {
    RenderResult r = render(scene, integrator);
    ASSERT_TRUE(r.scene.shading_normals());
    double most = 0;
    for (float v : r.image.xyz) most = std::max(most, std::abs(static_cast<double>(v)));
    for (float v : r.image.spectral) most = std::max(most, std::abs(static_cast<double>(v)));
    EXPECT_EQ(most, 0.0) << integrator << ": light leaked through the floor";
  }
}

// A UV sphere of `rings` × 2·`rings` quads with its vertices' exact normals.
std::string smooth_sphere(const std::string& name, double radius, const Eigen::Vector3d& c, int rings) {
  std::ostringstream s;
  const int segs = 2 * rings;
  for (int r = 0; r <= rings; ++r)
    for (int k = 0; k < segs; ++k) {
      double th = M_PI * r / rings, ph = 2 * M_PI * k / segs;
      Eigen::Vector3d n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      Eigen::Vector3d p = c + radius * n;
      s << "v " << p.x() << " " << p.y() << " " << p.z() << "\nvn " << n.x() << " " << n.y() << " "
        << n.z() << "\n";
    }
  auto id = [&](int r, int k) { return r * segs + (k % segs) + 1; };
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < segs; ++k) {
      int a = id(r, k), b = id(r + 1, k), d = id(r + 1, k + 1), e = id(r, k + 1);
      // Counter-clockwise seen from outside.
      if (r > 0) s << "f " << a << "//" << a << " " << b << "//" << b << " " << e << "//" << e << "\n";
      if (r < rings - 1) s << "f " << b << "//" << b << " " << d << "//" << d << " " << e << "//" << e << "\n";
    }
  return write_file(name, s.str());
}

TEST(ShadingNormals, LightTracingAndPhotonMappingAgreeWithBackwardOnASmoothShadedSphere) {
  const std::string obj = smooth_sphere("smooth_sphere.obj", 0.4, Eigen::Vector3d(0, 0, 0.4), 5);
  const std::string scene = write_file("smooth_sphere.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, -2.2, 1.4], "look_at": [0, 0, 0.3], "fov_deg": 50, "width": 24, "height": 24},
  "materials": {"black": {}, "white": {"passive": {"reflectance": 0.8}},
                "orange": {"passive": {"reflectance": {"nm": [380, 560, 600, 780], "value": [0.1, 0.1, 0.9, 0.9]}}},
                "gold": {"conductor": {"metal": "Au", "roughness": 0.2}}},
  "shapes": [
    {"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "white"},
    {"type": "obj", "file": ")" + obj + R"(", "material": "orange"},
    {"type": "obj", "file": ")" + obj + R"(", "material": "gold",
     "transform": {"scale": 0.6, "translate": [0.75, 0.3, -0.16]}},
    {"type": "quad", "corner": [-0.3, -0.3, 1.6], "u": [0, 0.6, 0], "v": [0.6, 0, 0], "material": "black",
     "emission": {"blackbody_K": 4000, "scale": 1e-6}}]})");
  RenderSettings b;
  b.spectral = false;
  b.passes = 4;
  b.integrator_settings.spp = 64;
  RenderResult backward = render_scene(scene, b);
  ASSERT_TRUE(backward.scene.shading_normals());
  std::map<std::string, std::vector<size_t>> regions =
      primary_hit_regions(backward.scene, backward.scene.camera);
  ASSERT_GE(regions["orange"].size(), 30u);
  ASSERT_GE(regions["gold"].size(), 10u);
  for (const char* integrator : {"forward", "photon"}) {
    RenderSettings o = b;
    o.integrator = integrator;
    o.integrator_settings.photons = 1 << 19;
    if (o.integrator == "photon") {
      o.passes = 16;
      o.integrator_settings.spp = 16;
      o.integrator_settings.photons = 1 << 17;
    }
    RenderResult other = render_scene(scene, o);
    for (const auto& [name, pixels] : regions) {
      if (name == "lamp") continue;
      BinStats t = pixel_statistics(other.image, false, pixels);
      BinStats d = difference_statistics(other.image, backward.image, false, pixels);
      for (int k = 0; k < 3; ++k) {
        const double ref = t.mean[k] - d.mean[k];
        std::printf("  %-7s %-6s row %d: %s/backward - 1 = %+.2f %% (± %.2f %%)\n", integrator, name.c_str(), k,
                    integrator, 100 * d.mean[k] / ref, 100 * d.standard_error[k] / ref);
        if (o.integrator == "forward")
          EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k]) << integrator << " " << name << " row " << k;
        else
          EXPECT_LT(std::abs(d.mean[k]), 0.03 * ref) << integrator << " " << name << " row " << k;
      }
    }
  }
}

}  // namespace
