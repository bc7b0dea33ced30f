#include "furnace_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/integrator_registry.h"
#include "render_support.h"
#include "scene/scene.h"
#include "study/furnace.h"
#include "test_support.h"

namespace kasha::test {

const GridRequest kFurnaceGrid{380, 780, 20};

std::string with_clay(const std::string& members) {
  const std::string clay =
      R"("clay": {"passive": {"reflectance": {"nm": [380, 450, 550, 650, 780], "value": [0.2, 0.35, 0.6, 0.7, 0.65]}}})";
  return "{" + clay + (members.empty() ? "" : ", " + members) + "}";
}

std::string furnace_scene(const std::string& materials, const std::string& wall,
                          const std::optional<FurnaceObject>& object, const std::string& textures) {
  std::string s = R"({"kasha_scene": 1, "textures": )" + textures + R"(,
  "camera": {"position": [0.2, -0.1, 0.3], "look_at": [1, 0.3, -0.5], "fov_deg": 60, "width": 16, "height": 16},
  "materials": )" +
                  materials + R"(,
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": ")" +
                  wall + R"(", "inward": true, "emission": {"csv": ")" +
                  source_path("scenes/data/CIE_D65_300_780.csv") + R"(", "scale": 0.01}})";
  if (object) {
    // In view: ahead of the camera; else behind it, where no camera ray meets it.
    const char* center = object->in_view ? "[0.8, 0.25, -0.4]" : "[-0.5, -0.4, 0.9]";
    s += R"(, {"type": "sphere", "center": )" + std::string(center) + R"(, "radius": )" +
         std::to_string(object->radius) + R"(, "material": ")" + object->material + "\"}";
  }
  return s + "]}";
}

std::vector<double> furnace_radiance(const std::string& json, const GridRequest& grid) {
  Furnace f = analyze_furnace(load_scene(write_file("furnace_truth.json", json), grid));
  EXPECT_TRUE(f.qualifies) << f.why_not;
  return f.radiance;
}

void expect_furnace_render(const std::string& integrator, const std::string& scene,
                           const std::vector<double>& truth) {
  const IntegratorInfo& info = IntegratorRegistry::find(integrator);
  RenderSettings s;
  s.integrator = integrator;
  s.grid = kFurnaceGrid;
  s.integrator_settings.spp = 8;
  s.integrator_settings.photons = integrator == "ppm" ? 1 << 15 : 1 << 13;
  s.passes = info.traits.unbiased ? 12 : 16;
  RenderResult r = render_scene(write_file("furnace_" + integrator + ".json", scene), s);
  BinStats st = pixel_statistics(r.image, true);
  double worst = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    worst = std::max(worst, std::abs(st.mean[i] / truth[i] - 1));
  std::printf("  %s: worst bin of the image mean off the furnace by %.4f\n", integrator.c_str(),
              worst);
  expect_bins_match(r, truth, info.traits.unbiased ? 0.02 : 0.04, integrator, info.traits.unbiased);
}

}  // namespace kasha::test
