#include "instanced_scene.h"

#include <Eigen/Geometry>
#include <sstream>
#include <vector>

#include "test_support.h"

namespace kasha::test {

namespace {

std::string matrix_json(const Eigen::Affine3d& m) {
  std::ostringstream out;
  out.precision(17);
  out << "{\"matrix\": [";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out << (r + c ? ", " : "") << m.matrix()(r, c);
  out << "]}";
  return out.str();
}

// The object's shapes, each under `place` (its own transform first).
std::vector<std::string> object_shapes(const Eigen::Affine3d& place) {
  const std::string torus = source_path("scenes/meshes/torus.obj");
  Eigen::Affine3d own = Eigen::Affine3d::Identity();
  own.scale(0.3);
  return {R"({"type": "obj", "file": ")" + torus + R"(", "material": "m", "transform": )" +
              matrix_json(place * own) + "}",
          R"({"type": "sphere", "center": [0.5, 0, 0], "radius": 0.2, "segments": 16,
             "material": "g", "transform": )" +
              matrix_json(place) + "}"};
}

std::vector<Eigen::Affine3d> placements() {
  std::vector<Eigen::Affine3d> out;
  for (int i = 0; i < 9; ++i) {
    Eigen::Affine3d m = Eigen::Affine3d::Identity();
    m.translate(Eigen::Vector3d(-2.2 + 2.2 * (i % 3), -1.2, -2.2 + 2.2 * (i / 3)));
    m.rotate(Eigen::AngleAxisd(0.7 * i, Eigen::Vector3d(1, 2, 0.5 * i).normalized()));
    m.scale(Eigen::Vector3d(1.0 + 0.1 * i, 1.3 - 0.05 * i, i == 4 ? -1.0 : 0.9));  // 4 mirrors
    out.push_back(m);
  }
  return out;
}

}  // namespace

std::string instanced_scene(bool flattened) {
  std::string shapes = R"(
      {"type": "box", "min": [-4, -2, -4], "max": [4, 3, 4], "material": "m", "inward": true},
      {"type": "quad", "corner": [-1, 2.99, -1], "u": [2, 0, 0], "v": [0, 0, 2], "material": "m",
       "emission": {"blackbody_K": 4000, "scale": 1e-6}})";
  std::string objects, instances;
  Eigen::Affine3d once = Eigen::Affine3d::Identity();
  once.translate(Eigen::Vector3d(0, 1.2, 0));
  const std::string single =
      R"({"type": "box", "min": [-0.3, -0.3, -0.3], "max": [0.3, 0.3, 0.3], "material": "g"})";
  if (flattened) {
    for (const Eigen::Affine3d& p : placements())
      for (const std::string& s : object_shapes(p)) shapes += ",\n      " + s;
    shapes += ",\n      " + single.substr(0, single.size() - 1) +
              ", \"transform\": " + matrix_json(once) + "}";
  } else {
    std::string parts;
    for (const std::string& s : object_shapes(Eigen::Affine3d::Identity()))
      parts += (parts.empty() ? "" : ", ") + s;
    objects = R"(, "objects": {"thing": [)" + parts + R"(], "single": [)" + single + "]}";
    for (const Eigen::Affine3d& p : placements())
      instances += std::string(instances.empty() ? "" : ", ") +
                   R"({"object": "thing", "transform": )" + matrix_json(p) + "}";
    instances = R"(, "instances": [)" + instances + R"(, {"object": "single", "transform": )" +
                matrix_json(once) + "}]";
  }
  return write_file(flattened ? "instanced_flat.json" : "instanced.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 1.5, -3.9], "look_at": [0, -0.5, 0], "fov_deg": 80,
               "width": 32, "height": 32},
    "materials": {"m": {"passive": {"reflectance": 0.6}},
                  "g": {"passive": {"reflectance": 0.3}, "gloss": {"reflectance": 0.1, "mirror": true}}},
    "shapes": [)" + shapes + "]" + objects + instances + "}");
}

}  // namespace kasha::test
