#pragma once
// A grey or textured floor (the quad z = 0, −2 ≤ x, y ≤ 2) seen from above by a 24 × 24 camera,
// rendered and compared with the radiance a test knows analytically at every floor point: the
// truth averaged over 16 × 16 points in each pixel (as the film's box filter averages it), the
// residuals' mean in four rings about the image centre within 4 standard errors (of the residuals
// themselves) plus 1 % of the truth there, for every bin.
#include <Eigen/Dense>
#include <functional>
#include <string>

#include "scene/scene.h"

namespace kasha::test {

constexpr int kFloorSize = 24;

// Writes a scene named `name` (scratch folder) with the floor of material `floor` (a JSON
// material), `lights` (a JSON array's contents), `extra` top-level entries (e.g. "textures") and
// `floor_keys` added to the floor shape (e.g. its "emission"), and `shapes` after it.
std::string floor_scene(const std::string& name, const std::string& floor,
                        const std::string& lights, const std::string& extra = "",
                        const std::string& floor_keys = "", const std::string& shapes = "");

// The floor point the camera ray through the film position (x, y) hits.
Eigen::Vector3d floor_point(const KCamera& camera, double x, double y);

// The radiance leaving the floor point towards the camera, in bin i of the scene.
using FloorRadiance = std::function<double(const Scene&, const Eigen::Vector3d&, int)>;

void expect_floor(const std::string& scene, const std::string& integrator,
                  const FloorRadiance& radiance, int spp, long long photons, int passes);

}  // namespace kasha::test
