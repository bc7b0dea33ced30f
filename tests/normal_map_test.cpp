// Normal maps (a material's "normal_map", kernels/materials/normal_map.h, pbrt-v4's NormalMap):
// - a map of the unperturbed normal (0.5, 0.5, 1) leaves a lit room's image as it was, within
//   noise, in backward and vcm;
// - a constant map leaning 20° towards a distant light at 45° shows ρ/π·E·cos 25° (the light's
//   angle to the mapped normal) in backward and vcm, on a floor whose ∂p/∂u runs along +x (the
//   map's x) and on one whose ∂p/∂u runs along +y (the map's y is then n × ∂p/∂u = −x);
// - a mix's normal map is refused; the pbrt importer passes "normalmap" through.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "render_support.h"
#include "scene/pbrt/pbrt_import.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

// A 1 × 1 PFM image of rgb (exact floats, so 2·rgb − 1 is the normal asked for).
std::string constant_map(const std::string& name, float r, float g, float b) {
  std::string pfm = "PF\n1 1\n-1.0\n";
  const float v[3] = {r, g, b};
  pfm.append(reinterpret_cast<const char*>(v), sizeof v);
  return write_file(name, pfm);
}

// The map of the tangent-space normal n.
std::string normal_map_of(const std::string& name, double x, double y, double z) {
  return constant_map(name, static_cast<float>((x + 1) / 2), static_cast<float>((y + 1) / 2),
                      static_cast<float>((z + 1) / 2));
}

RenderResult render(const std::string& scene, const std::string& integrator, int spp) {
  RenderSettings s;
  s.integrator = integrator;
  s.spectral = false;
  s.passes = 4;
  s.integrator_settings.spp = spp;
  s.integrator_settings.photons = 1 << 18;
  return render_scene(scene, s);
}

// A floor, a box and a wall under a lamp, every surface's material `material`.
std::string room(const std::string& name, const std::string& material) {
  return write_file(name, R"({"kasha_scene": 1,
  "camera": {"position": [0, -2.5, 1.5], "look_at": [0, 0, 0.4], "fov_deg": 50, "width": 16, "height": 16},
  "materials": {"black": {}, "white": )" +
                              material + R"(},
  "shapes": [
    {"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0], "material": "white"},
    {"type": "quad", "corner": [-2, 1, 0], "u": [4, 0, 0], "v": [0, 0, 2], "material": "white"},
    {"type": "box", "min": [-0.4, -0.4, 0], "max": [0.4, 0.4, 0.6], "material": "white"},
    {"type": "quad", "corner": [-0.3, -0.3, 1.6], "u": [0, 0.6, 0], "v": [0.6, 0, 0], "material": "black",
     "emission": 10}]})");
}

TEST(NormalMaps, AMapOfTheUnperturbedNormalChangesNothing) {
  const std::string flat = normal_map_of("flat_map.pfm", 0, 0, 1);
  const std::string plain = room("plain_room.json", R"({"passive": {"reflectance": 0.7}})");
  const std::string mapped = room(
      "mapped_room.json", R"({"passive": {"reflectance": 0.7}, "normal_map": ")" + flat + "\"}");
  for (const char* integrator : {"backward", "vcm"}) {
    RenderResult a = render(plain, integrator, 16), b = render(mapped, integrator, 16);
    ASSERT_TRUE(b.scene.normal_mapped());
    ASSERT_FALSE(a.scene.normal_mapped());
    BinStats t = pixel_statistics(a.image, false);
    BinStats d = difference_statistics(b.image, a.image, false);
    for (int k = 0; k < 3; ++k) {
      std::printf("  %-8s row %d: mapped/plain - 1 = %+.3f %% (± %.3f %%)\n", integrator, k,
                  100 * d.mean[k] / t.mean[k], 100 * d.standard_error[k] / t.mean[k]);
      EXPECT_GT(t.mean[k], 0) << integrator;
      EXPECT_LT(std::abs(d.mean[k]), 4 * d.standard_error[k] + 1e-4 * t.mean[k])
          << integrator << " row " << k;
    }
  }
}

// The floor −2 ≤ x, y ≤ 2 at z = 0 facing +z, its ∂p/∂u along `u`, under a distant light from
// (1, 0, 1); its map the tangent-space normal (x, y, z).
std::string lit_floor(const std::string& name, const std::string& corner, const std::string& u,
                      const std::string& v, double x, double y, double z) {
  const std::string map = normal_map_of(name + ".pfm", x, y, z);
  return write_file(name + ".json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 30, "width": 16, "height": 16},
  "materials": {"grey": {"passive": {"reflectance": 0.5}, "normal_map": ")" +
                                        map + R"("}},
  "shapes": [{"type": "quad", "corner": )" +
                                        corner + R"(, "u": )" + u + R"(, "v": )" + v +
                                        R"(, "material": "grey"}],
  "lights": [{"type": "distant", "from": [1, 0, 1], "to": [0, 0, 0],
              "irradiance": {"nm": [380, 780], "value": [1, 2]}}]})");
}

TEST(NormalMaps, AFloorIsLitAsItsMappedNormalFacesTheLight) {
  const double s = std::sin(20 * M_PI / 180), c = std::cos(20 * M_PI / 180);
  // ∂p/∂u = +x: the map's x is +x. ∂p/∂u = +y: the map's y is n × ∂p/∂u = −x.
  const std::string along_x =
      lit_floor("mapped_floor_x", "[-2, -2, 0]", "[4, 0, 0]", "[0, 4, 0]", s, 0, c);
  const std::string along_y =
      lit_floor("mapped_floor_y", "[2, -2, 0]", "[0, 4, 0]", "[-4, 0, 0]", 0, -s, c);
  for (const std::string& scene : {along_x, along_y})
    for (const char* integrator : {"backward", "vcm"}) {
      RenderSettings st;
      st.integrator = integrator;
      st.passes = 4;
      st.integrator_settings.spp = 16;
      RenderResult r = render_scene(scene, st);
      ASSERT_TRUE(r.scene.normal_mapped());
      const std::vector<double>& e = r.scene.lights.front().per_bin;
      std::vector<double> truth(e.size());
      for (size_t i = 0; i < e.size(); ++i)
        truth[i] = 0.5 / M_PI * e[i] * std::cos(25 * M_PI / 180);
      expect_bins_match(r, truth, 0.02, scene + " " + integrator);
    }
}

TEST(NormalMaps, AMixsNormalMapIsRefused) {
  const std::string map = normal_map_of("mix_map.pfm", 0, 0, 1);
  const std::string scene = write_file("mix_normal_map.json", R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov_deg": 30, "width": 8, "height": 8},
  "materials": {"a": {"passive": {"reflectance": 0.5}}, "b": {"passive": {"reflectance": 0.2}},
                "m": {"mix": {"materials": ["a", "b"], "amount": 0.5}, "normal_map": ")" +
                                                                  map + R"("}},
  "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0], "material": "m",
              "emission": 1}]})");
  CommandResult r = run_kasha("info " + scene);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("a mix's normal maps are its materials' own"), std::string::npos) << r.err;
}

TEST(NormalMaps, ThePbrtImporterPassesNormalmapThrough) {
  normal_map_of("pbrt_map.pfm", 0, 0, 1);
  const std::string file = write_file("normal_mapped.pbrt", R"(LookAt 0 1 3  0 1 0  0 1 0
Camera "perspective" "float fov" 45
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "distant" "point3 from" [0 1 0] "point3 to" [0 0 0]
Material "diffuse" "string normalmap" "pbrt_map.pfm"
Shape "trianglemesh" "point3 P" [-1 0 -1  1 0 -1  1 0 1  -1 0 1] "integer indices" [0 1 2  0 2 3]
)");
  const nlohmann::json s = import_pbrt_scene(file, {});
  bool found = false;
  for (const auto& [name, m] : s.at("materials").items())
    if (m.contains("normal_map")) found = m.at("normal_map") == "pbrt_map.pfm";
  EXPECT_TRUE(found) << s.at("materials").dump();
  const Scene loaded = load_scene(file);
  EXPECT_TRUE(loaded.normal_mapped());
  ASSERT_EQ(loaded.normal_maps.size(), 1u);
  EXPECT_TRUE(
      std::filesystem::equivalent(loaded.normal_maps[0].file, scratch_dir() / "pbrt_map.pfm"));
  CommandResult r = run_kasha("info " + file);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("normal map"), std::string::npos) << r.err;
}

}  // namespace
