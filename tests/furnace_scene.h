#pragma once
// The passive furnace the material tests put their materials in: an emitting sphere seen from
// inside, whose uniform radiance analyze_furnace gives, with a tested sphere in it or the tested
// material as its wall; and the check of one integrator's render against that radiance.
#include <optional>
#include <string>
#include <vector>

#include "spectrum/wavelength_grid.h"

namespace kasha::test {

// The furnace tests' bins: 20 nm over the visible.
extern const GridRequest kFurnaceGrid;

// `{"clay": {…}, members}`: the usual wall, a Lambert reflectance rising from 0.2 to 0.7, beside
// the tested materials (`members`: JSON object members without braces, or empty).
std::string with_clay(const std::string& members);

// A sphere of `material` inside the enclosure: in view of the camera, or behind it for the
// integrators that do not see delta surfaces from the camera (light tracing).
struct FurnaceObject {
  std::string material;
  double radius = 0;
  bool in_view = true;
};

// The enclosure: a sphere of radius 2 and material `wall` emitting the D65-like spectrum inwards,
// with `object` in it; `materials` and `textures` are the scene's JSON objects.
std::string furnace_scene(const std::string& materials, const std::string& wall = "clay",
                          const std::optional<FurnaceObject>& object = std::nullopt,
                          const std::string& textures = "{}");

// analyze_furnace's radiance for the scene `json` at `grid` (a failure where it is no furnace).
std::vector<double> furnace_radiance(const std::string& json,
                                     const GridRequest& grid = kFurnaceGrid);

// `scene` (JSON) rendered by `integrator` at kFurnaceGrid, 8 paths a pixel and the photons and
// passes it needs, matches `truth` in every bin: within 2 % and its noise if it is unbiased, 4 %
// if it is consistent.
void expect_furnace_render(const std::string& integrator, const std::string& scene,
                           const std::vector<double>& truth);

}  // namespace kasha::test
