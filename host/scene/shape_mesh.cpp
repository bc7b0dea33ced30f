#include "scene/shape_mesh.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "scene/limits.h"

namespace kasha {

ShapeMesh quad_triangles(const Eigen::Vector3d& c, const Eigen::Vector3d& u,
                         const Eigen::Vector3d& v) {
  // Both triangles face u × v.
  const Eigen::Vector2d a(0, 0), b(1, 0), d(1, 1), e(0, 1);
  return {{Triangle{c, c + u, c + u + v}, Triangle{c, c + u + v, c + v}},
          {TriangleUv{a, b, d}, TriangleUv{a, d, e}},
          {}};
}

ShapeMesh box_triangles(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Eigen::Vector3d d = hi - lo;
  Eigen::Vector3d ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  ShapeMesh out;
  auto add = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    ShapeMesh q = quad_triangles(c, u, v);
    out.tris.insert(out.tris.end(), q.tris.begin(), q.tris.end());
    out.uv.insert(out.uv.end(), q.uv.begin(), q.uv.end());
  };
  add(lo, ez, ey);       // -x: ez × ey = -x
  add(lo + ex, ey, ez);  // +x
  add(lo, ex, ez);       // -y: ex × ez = -y
  add(lo + ey, ez, ex);  // +y
  add(lo, ey, ex);       // -z: ey × ex = -z
  add(lo + ez, ex, ey);  // +z
  return out;
}

ShapeMesh sphere_triangles(const Eigen::Vector3d& center, double radius, int segments) {
  int rings = std::max(2, segments / 2);
  auto point = [&](int ring, int seg) {
    double theta = M_PI * ring / rings, phi = 2.0 * M_PI * seg / segments;
    return Eigen::Vector3d(center + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                             std::cos(theta),
                                                             std::sin(theta) * std::sin(phi)));
  };
  auto uv = [&](int ring, int seg) {
    return Eigen::Vector2d(double(seg) / segments, double(ring) / rings);
  };
  ShapeMesh out;
  out.tris.reserve(2 * static_cast<size_t>(rings) * segments);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      Eigen::Vector3d a = point(r, s), b = point(r, s + 1), c = point(r + 1, s),
                      d = point(r + 1, s + 1);
      // Outward winding; the pole rows collapse to one triangle each.
      if (r > 0) {
        out.tris.push_back({a, b, c});
        out.uv.push_back({uv(r, s), uv(r, s + 1), uv(r + 1, s)});
      }
      if (r < rings - 1) {
        out.tris.push_back({b, d, c});
        out.uv.push_back({uv(r, s + 1), uv(r + 1, s + 1), uv(r + 1, s)});
      }
    }
  return out;
}

namespace {

// The words of an OBJ line after its keyword, split at spaces and tabs as tinyobjloader does.
std::vector<std::string> obj_words(const std::string& line, size_t from) {
  std::vector<std::string> out;
  while (from < line.size()) {
    size_t start = line.find_first_not_of(" \t", from);
    if (start == std::string::npos) break;
    size_t end = std::min(line.find_first_of(" \t", start), line.size());
    out.push_back(line.substr(start, end - start));
    from = end;
  }
  return out;
}

// A whole word of decimal notation: tinyobjloader reads nothing else ("nan", "inf", hex) and
// silently stores 0 instead.
bool obj_coordinate(const std::string& word, double& out) {
  if (word.empty() || word.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  char* end = nullptr;
  out = std::strtod(word.c_str(), &end);
  return end == word.c_str() + word.size();
}

// tinyobjloader gives no line numbers, stores 0 for an unreadable or missing coordinate without a
// word, and reads past its vertex array for a polygon with an index out of range. So the `v` and
// `f` lines are checked first, each error naming its line; the geometry still comes from it.
// Indices are read as 64-bit numbers, so one beyond 32 bits is out of range, not wrapped.
void check_obj_lines(const std::string& path, const std::string& text) {
  long vertices = 0;
  int line_no = 0;
  for (size_t pos = 0; pos < text.size();) {
    // A line ends at "\n", "\r\n" or "\r", as tinyobjloader splits them.
    size_t end = std::min(text.find_first_of("\r\n", pos), text.size());
    const std::string line = text.substr(pos, end - pos);
    pos = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++line_no;
    size_t k = line.find_first_not_of(" \t");
    if (k == std::string::npos || k + 1 >= line.size() ||
        (line[k + 1] != ' ' && line[k + 1] != '\t'))
      continue;
    const std::string at = path + ": line " + std::to_string(line_no) + ": ";
    const std::vector<std::string> words = obj_words(line, k + 2);
    if (line[k] == 'v') {
      if (words.size() < 3)
        throw Error(at + "a vertex needs x, y and z, found " + std::to_string(words.size()) +
                    " number" + (words.size() == 1 ? "" : "s"));
      double p[3];
      for (int c = 0; c < 3; ++c)
        if (!obj_coordinate(words[c], p[c]) || !std::isfinite(p[c]))
          throw Error(at + "vertex coordinate \"" + printable(words[c]) +
                      "\" is not a finite number");
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(p[c]) <= kMaxCoordinate)) {
          char v[128];
          std::snprintf(v, sizeof v, "(%g, %g, %g)", p[0], p[1], p[2]);
          throw Error(at + "a vertex at " + v + " is beyond ±1e18");
        }
      ++vertices;
    } else if (line[k] == 'f') {
      for (const std::string& word : words) {
        // The vertex number leads each of i, i/j, i/j/k and i//k; negative ones count back.
        const std::string number = word.substr(0, word.find('/'));
        char* rest = nullptr;
        errno = 0;
        long i = std::strtol(number.c_str(), &rest, 10);
        if (number.empty() || *rest != '\0' || errno != 0 || i == 0 || i > vertices ||
            -i > vertices)
          throw Error(at + "face vertex \"" + printable(word) + "\" names no vertex (" +
                      std::to_string(vertices) + " defined above it)");
      }
    }
  }
}

}  // namespace

ShapeMesh obj_triangles(const std::string& path) {
  // Read once through the checked route (regular file, size limit); tinyobjloader then parses the
  // same text and opens nothing itself (no .mtl either: kasha takes materials from the scene).
  const std::string text = read_input_file(path, kMaxBinaryInputBytes);
  check_obj_lines(path, text);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    for (char& ch : why)
      if (ch == '\n') ch = ' ';
    throw Error(printable(path) +
                ": cannot read OBJ mesh: " + (why.empty() ? "unknown error" : printable(why)));
  }
  const auto& v = reader.GetAttrib().vertices;
  const auto& vt = reader.GetAttrib().texcoords;
  const auto& vn = reader.GetAttrib().normals;
  ShapeMesh out;
  bool any_normals = false;
  const TriangleUv fallback = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)};
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
      Triangle t;
      TriangleUv uv = fallback;
      TriangleNormals normals;
      bool has_uv = true, has_normals = true;
      for (int k = 0; k < 3; ++k) {
        int i = idx[f + k].vertex_index;
        if (i < 0 || 3 * static_cast<size_t>(i) + 2 >= v.size())
          throw Error(path + ": face " + std::to_string(f / 3 + 1) + " refers to a missing vertex");
        t[k] = Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        int j = idx[f + k].texcoord_index;
        if (j < 0 || 2 * static_cast<size_t>(j) + 1 >= vt.size() || !std::isfinite(vt[2 * j]) ||
            !std::isfinite(vt[2 * j + 1]))
          has_uv = false;
        else
          uv[k] = Eigen::Vector2d(vt[2 * j], vt[2 * j + 1]);
        int n = idx[f + k].normal_index;
        if (n < 0 || 3 * static_cast<size_t>(n) + 2 >= vn.size()) {
          has_normals = false;
        } else {
          normals[k] = Eigen::Vector3d(vn[3 * n], vn[3 * n + 1], vn[3 * n + 2]);
          // A zero, infinite or NaN normal says nothing: the face is shaded flat.
          const double length = normals[k].norm();
          if (!(length > 0 && std::isfinite(length)))
            has_normals = false;
          else
            normals[k] /= length;
        }
      }
      out.tris.push_back(t);
      out.uv.push_back(has_uv ? uv : fallback);
      if (!has_normals) {
        const Eigen::Vector3d g = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
        normals = {g, g, g};
      }
      any_normals = any_normals || has_normals;
      out.normals.push_back(normals);
    }
  }
  if (out.tris.empty()) throw Error(path + ": OBJ mesh has no faces");
  if (!any_normals) out.normals.clear();
  return out;
}

void flip_triangles(ShapeMesh& mesh) {
  for (Triangle& t : mesh.tris) std::swap(t[1], t[2]);
  for (TriangleUv& t : mesh.uv) std::swap(t[1], t[2]);
  for (TriangleNormals& t : mesh.normals) std::swap(t[1], t[2]);
}

void transform_triangles(ShapeMesh& mesh, const Eigen::Affine3d& m) {
  for (Triangle& t : mesh.tris)
    for (Eigen::Vector3d& p : t) p = m * p;
  const Eigen::Matrix3d normal_matrix = m.linear().inverse().transpose();
  for (TriangleNormals& t : mesh.normals)
    for (Eigen::Vector3d& n : t) n = (normal_matrix * n).normalized();
  if (m.linear().determinant() < 0) flip_triangles(mesh);
}

}  // namespace kasha
