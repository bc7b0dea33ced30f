#include "scene/shape_mesh.h"

#include <tiny_obj_loader.h>

#include <cmath>

#include "core/error.h"

namespace kasha {

std::vector<Triangle> quad_triangles(const Eigen::Vector3d& c, const Eigen::Vector3d& u,
                                     const Eigen::Vector3d& v) {
  // Both triangles face u × v.
  return {Triangle{c, c + u, c + u + v}, Triangle{c, c + u + v, c + v}};
}

std::vector<Triangle> box_triangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Eigen::Vector3d d = hi - lo;
  Eigen::Vector3d ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  std::vector<Triangle> out;
  auto add = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    for (const Triangle& t : quad_triangles(c, u, v)) out.push_back(t);
  };
  add(lo, ez, ey);       // -x: ez × ey = -x
  add(lo + ex, ey, ez);  // +x
  add(lo, ex, ez);       // -y: ex × ez = -y
  add(lo + ey, ez, ex);  // +y
  add(lo, ey, ex);       // -z: ey × ex = -z
  add(lo + ez, ex, ey);  // +z
  return out;
}

std::vector<Triangle> sphere_triangles(const Eigen::Vector3d& center, double radius, int segments) {
  int rings = std::max(2, segments / 2);
  auto point = [&](int ring, int seg) {
    double theta = M_PI * ring / rings, phi = 2.0 * M_PI * seg / segments;
    return Eigen::Vector3d(center + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                             std::cos(theta),
                                                             std::sin(theta) * std::sin(phi)));
  };
  std::vector<Triangle> out;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      Eigen::Vector3d a = point(r, s), b = point(r, s + 1), c = point(r + 1, s),
                      d = point(r + 1, s + 1);
      // Outward winding; the pole rows collapse to one triangle each.
      if (r > 0) out.push_back({a, b, c});
      if (r < rings - 1) out.push_back({b, d, c});
    }
  return out;
}

std::vector<Triangle> obj_triangles(const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    for (char& ch : why)
      if (ch == '\n') ch = ' ';
    throw Error(path + ": cannot read OBJ mesh: " + (why.empty() ? "unknown error" : why));
  }
  const auto& v = reader.GetAttrib().vertices;
  std::vector<Triangle> out;
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        int i = idx[f + k].vertex_index;
        if (i < 0 || 3 * static_cast<size_t>(i) + 2 >= v.size())
          throw Error(path + ": face " + std::to_string(f / 3 + 1) + " refers to a missing vertex");
        t[k] = Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
      }
      out.push_back(t);
    }
  }
  if (out.empty()) throw Error(path + ": OBJ mesh has no faces");
  return out;
}

void flip_triangles(std::vector<Triangle>& tris) {
  for (Triangle& t : tris) std::swap(t[1], t[2]);
}

void transform_triangles(std::vector<Triangle>& tris, const Eigen::Affine3d& m) {
  for (Triangle& t : tris)
    for (Eigen::Vector3d& p : t) p = m * p;
  if (m.linear().determinant() < 0) flip_triangles(tris);
}

}  // namespace kasha
