#include "scene/pbrt/pbrt_shapes.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/printable.h"
#include "scene/pbrt/pbrt_subdivision.h"

namespace kasha {

namespace {

// A grid of (u, v) samples, `nu` × `nv` cells, as indexed triangles: each cell two triangles
// wound so that their normal is ∂p/∂u × ∂p/∂v (pbrt-v4's orientation of its quadrics).
struct GridMesh {
  std::vector<double> positions, normals, uvs;
  std::vector<double> indices;
};

template <typename Point>
GridMesh grid_mesh(int nu, int nv, const Point& point) {
  GridMesh g;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double u = double(i) / nu, v = double(j) / nv;
      Eigen::Vector3d p, n;
      point(u, v, p, n);
      for (int k = 0; k < 3; ++k) {
        g.positions.push_back(p[k]);
        g.normals.push_back(n[k]);
      }
      g.uvs.push_back(u);
      g.uvs.push_back(v);
    }
  const auto at = [&](int i, int j) { return double(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      for (double x : {at(i, j), at(i + 1, j), at(i + 1, j + 1)}) g.indices.push_back(x);
      for (double x : {at(i, j), at(i + 1, j + 1), at(i, j + 1)}) g.indices.push_back(x);
    }
  return g;
}

nlohmann::json triangles_json(const GridMesh& g, bool with_normals) {
  nlohmann::json s = {
      {"type", "triangles"}, {"positions", g.positions}, {"indices", g.indices}, {"uvs", g.uvs}};
  if (with_normals) s["normals"] = g.normals;
  return s;
}

double radians(double deg) {
  return deg * M_PI / 180.0;
}

// pbrt-v4's phimax, clamped to [0, 360] as it does.
double phi_max(const PbrtParameters& params) {
  return radians(std::clamp(params.get_float("phimax", 360), 0.0, 360.0));
}

void check_positive(const PbrtParameters& params, const char* name, double value,
                    const PbrtLocation& where) {
  if (!(value > 0)) {
    const PbrtParameter* p = params.find(name, "float");
    pbrt_fail(p ? p->where : where, std::string("\"") + name + "\" must be positive");
  }
}

// Three numbers of `xyz` (x y z per vertex) as vertex i.
Eigen::Vector3d vertex(const std::vector<double>& xyz, size_t i) {
  return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

// A mesh's arrays as its parameters give them (uv as u v per vertex), checked against each other.
struct MeshArrays {
  std::vector<double> p, indices, n, uv;
};

MeshArrays read_mesh(const std::string& type, const PbrtParameters& params,
                     const PbrtLocation& where) {
  MeshArrays m;
  m.p = params.get_numbers("P", "point3");
  m.indices = params.get_numbers("indices", "integer");
  const int corners = type == "bilinearmesh" ? 4 : 3;
  if (m.p.empty()) pbrt_fail(where, "Shape " + in_quotes(type) + " has no \"P\"");
  if (m.indices.empty() && m.p.size() == size_t(3 * corners))
    for (int i = 0; i < corners; ++i) m.indices.push_back(i);
  if (m.indices.empty() || m.indices.size() % corners != 0)
    pbrt_fail(where, "Shape " + in_quotes(type) + ": \"indices\" must come in groups of " +
                         std::to_string(corners));
  const double vertices = double(m.p.size() / 3);
  for (double i : m.indices)
    if (i < 0 || i >= vertices || i != std::floor(i))
      pbrt_fail(where, "Shape " + in_quotes(type) + ": index " + std::to_string(i) +
                           " names no vertex of \"P\" (" + std::to_string(m.p.size() / 3) +
                           " vertices)");
  m.n = params.get_numbers("N", "normal3");
  m.uv = params.get_numbers("uv", "point2");
  if (!m.n.empty() && m.n.size() != m.p.size())
    pbrt_fail(where, "Shape " + in_quotes(type) + ": \"N\" must give one normal per vertex");
  if (!m.uv.empty() && m.uv.size() / 2 != m.p.size() / 3)
    pbrt_fail(where, "Shape " + in_quotes(type) + ": \"uv\" must give one point per vertex");
  if (params.find("S", "vector3"))
    pbrt_warn(where, "tangents \"S\" are not used by kasha (its tangent frames follow the normal)");
  params.get_numbers("faceIndices", "integer");  // per-face ids for pbrt's ptex textures
  return m;
}

// pbrt-v4 subdivides a loopsubdiv and keeps positions and normals only.
void subdivide(const PbrtParameters& params, const PbrtLocation& where, MeshArrays& m) {
  const int levels = params.get_int("levels", 3);
  if (levels < 0 || levels > 10) pbrt_fail(where, "loopsubdiv: \"levels\" must lie in [0, 10]");
  if (double(m.indices.size() / 3) * std::pow(4.0, levels) > double(kMaxSubdividedTriangles))
    pbrt_fail(where, "loopsubdiv: " + std::to_string(levels) + " levels make more than " +
                         std::to_string(kMaxSubdividedTriangles) + " triangles");
  if (!m.n.empty() || !m.uv.empty())
    pbrt_warn(where, "loopsubdiv: \"N\" and \"uv\" are not used (pbrt-v4 does not either)");
  const SubdividedMesh sub = loop_subdivide(m.p, m.indices, levels);
  m.p = sub.positions;
  m.indices = sub.indices;
  m.n = sub.normals;  // the faces' winding, so the turn to the normals keeps it
  m.uv.clear();
}

// Two triangles per bilinear patch (v00 v10 v01 v11): exact for flat patches, which is what
// exporters write; a curved patch is approximated by its two halves.
std::vector<double> bilinear_triangles(const MeshArrays& m, const PbrtLocation& where) {
  std::vector<double> tri;
  bool curved = false;
  for (size_t q = 0; q < m.indices.size(); q += 4) {
    const double a = m.indices[q], b = m.indices[q + 1], c = m.indices[q + 2], d = m.indices[q + 3];
    for (double x : {a, b, d, a, d, c}) tri.push_back(x);
    Eigen::Vector3d v[4];
    for (int k = 0; k < 4; ++k) v[k] = vertex(m.p, size_t(m.indices[q + k]));
    const Eigen::Vector3d nrm = (v[1] - v[0]).cross(v[2] - v[0]);
    const double size = (v[3] - v[0]).norm();
    if (nrm.norm() > 0 && std::abs(nrm.normalized().dot(v[3] - v[0])) > 1e-6 * size) curved = true;
  }
  if (curved)
    pbrt_warn(where, "bilinearmesh: curved patches are approximated by two triangles each");
  return tri;
}

// pbrt-v4 turns a triangle's geometric normal towards its shading normals; kasha keeps the
// winding as the front, so the winding is turned instead (an emitter emits on that side).
void wind_to_normals(MeshArrays& m) {
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    Eigen::Vector3d v[3], sum(0, 0, 0);
    for (int k = 0; k < 3; ++k) {
      const size_t i = size_t(m.indices[t + k]);
      v[k] = vertex(m.p, i);
      sum += vertex(m.n, i);
    }
    if ((v[1] - v[0]).cross(v[2] - v[0]).dot(sum) < 0)
      std::swap(m.indices[t + 1], m.indices[t + 2]);
  }
}

// trianglemesh, bilinearmesh and loopsubdiv as "triangles".
nlohmann::json mesh_shape(const std::string& type, const PbrtParameters& params,
                          const PbrtLocation& where) {
  MeshArrays m = read_mesh(type, params, where);
  if (type == "loopsubdiv") subdivide(params, where, m);
  if (type == "bilinearmesh") m.indices = bilinear_triangles(m, where);
  if (!m.n.empty() && type != "bilinearmesh") wind_to_normals(m);
  nlohmann::json shape = {{"type", "triangles"}, {"positions", m.p}, {"indices", m.indices}};
  if (!m.n.empty()) shape["normals"] = m.n;
  if (!m.uv.empty()) shape["uvs"] = m.uv;
  return shape;
}

nlohmann::json ply_shape(const PbrtParameters& params, const PbrtLocation& where) {
  const std::string file = params.get_string("filename", "");
  if (file.empty()) pbrt_fail(where, "Shape \"plymesh\" has no \"filename\"");
  if (params.find("displacement", "texture"))
    pbrt_warn(where, "plymesh: displacement is not built in kasha: the mesh is rendered as is");
  params.get_float("edgelength", 1);
  return {{"type", "mesh"}, {"file", file}};
}

nlohmann::json sphere_shape(const PbrtParameters& params, const PbrtLocation& where) {
  const double r = params.get_float("radius", 1);
  check_positive(params, "radius", r, where);
  const double z0 =
      std::clamp(std::min(params.get_float("zmin", -r), params.get_float("zmax", r)), -r, r);
  const double z1 =
      std::clamp(std::max(params.get_float("zmin", -r), params.get_float("zmax", r)), -r, r);
  const double t0 = std::acos(z0 / r), t1 = std::acos(z1 / r), phimax = phi_max(params);
  if (phimax == 0 || t0 == t1) pbrt_fail(where, "Shape \"sphere\" has no area");
  // pbrt-v4: φ = u·φmax from +x towards +y, θ = θ(zmin) + v·(θ(zmax) − θ(zmin)).
  const GridMesh g = grid_mesh(
      kPbrtSegments, kPbrtSegments / 2,
      [&](double u, double v, Eigen::Vector3d& pt, Eigen::Vector3d& nn) {
        const double phi = u * phimax, theta = t0 + v * (t1 - t0);
        nn = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
        pt = r * nn;
      });
  nlohmann::json s = triangles_json(g, true);  // ∂p/∂u × ∂p/∂v points out, as pbrt-v4's normal
  // A full sphere, as an emitter, is sampled by the solid angle it subtends (docs/lights.md).
  if (z0 == -r && z1 == r && phimax == radians(360))
    s["sphere"] = {{"center", {0, 0, 0}}, {"radius", r}};
  return s;
}

nlohmann::json cylinder_shape(const PbrtParameters& params, const PbrtLocation& where) {
  const double r = params.get_float("radius", 1);
  check_positive(params, "radius", r, where);
  const double z0 = params.get_float("zmin", -1), z1 = params.get_float("zmax", 1);
  const double phimax = phi_max(params);
  if (phimax == 0 || z0 == z1) pbrt_fail(where, "Shape \"cylinder\" has no area");
  const GridMesh g = grid_mesh(
      kPbrtSegments, 1, [&](double u, double v, Eigen::Vector3d& pt, Eigen::Vector3d& nn) {
        const double phi = u * phimax;
        nn = {std::cos(phi), std::sin(phi), 0};
        pt = {r * nn[0], r * nn[1], std::min(z0, z1) + v * std::abs(z1 - z0)};
      });
  return triangles_json(g, true);
}

nlohmann::json disk_shape(const PbrtParameters& params, const PbrtLocation& where) {
  const double h = params.get_float("height", 0), r = params.get_float("radius", 1);
  const double ri = params.get_float("innerradius", 0), phimax = phi_max(params);
  check_positive(params, "radius", r, where);
  if (!(ri >= 0 && ri < r))
    pbrt_fail(where, "Shape \"disk\": \"innerradius\" must lie in [0, radius)");
  if (phimax == 0) pbrt_fail(where, "Shape \"disk\" has no area");
  // pbrt-v4: u = φ/φmax, v = (r − ρ)/(r − ri); the normal is +z.
  const GridMesh g = grid_mesh(kPbrtSegments, 1,
                               [&](double u, double v, Eigen::Vector3d& pt, Eigen::Vector3d& nn) {
                                 const double phi = u * phimax, rho = r - v * (r - ri);
                                 pt = {rho * std::cos(phi), rho * std::sin(phi), h};
                                 nn = {0, 0, 1};
                               });
  return triangles_json(g, false);  // ∂p/∂u × ∂p/∂v is +z, pbrt-v4's normal
}

}  // namespace

nlohmann::json pbrt_shape(const std::string& type, const PbrtParameters& params,
                          const PbrtLocation& where) {
  params.find("alpha", "float texture");  // read by pbrt_shape_alpha: not an unused parameter
  nlohmann::json shape;
  if (type == "trianglemesh" || type == "bilinearmesh" || type == "loopsubdiv") {
    shape = mesh_shape(type, params, where);
  } else if (type == "plymesh") {
    shape = ply_shape(params, where);
  } else if (type == "sphere") {
    shape = sphere_shape(params, where);
  } else if (type == "cylinder") {
    shape = cylinder_shape(params, where);
  } else if (type == "disk") {
    shape = disk_shape(params, where);
  } else if (type == "curve") {
    pbrt_warn(where, "curves are not built in kasha: the shape is left out");
    for (const PbrtParameter& p : params.all()) p.used = true;
    return nullptr;
  } else {
    pbrt_fail(where, "unknown shape type " + in_quotes(type) +
                         " (kasha reads trianglemesh, plymesh, bilinearmesh, loopsubdiv, sphere, "
                         "cylinder, disk)");
  }
  params.warn_unused("Shape " + in_quotes(type));
  return shape;
}

void pbrt_shape_alpha(const PbrtParameters& params, const PbrtTextures& textures,
                      nlohmann::json& shape) {
  const PbrtParameter* a = params.find("alpha", "float texture");
  if (!a) return;
  if (a->type == "texture" && a->strings.size() == 1) {
    auto t = textures.scalar.find(a->strings[0]);
    if (t != textures.scalar.end() && !t->second.kasha_name.empty()) {
      shape["alpha"] = t->second.kasha_name;  // its factor is in it (pbrt_textures.cpp)
      return;
    }
  }
  // A number, or a constant texture: pbrt-v4 keeps every hit at 1 or more, none at 0 or less.
  const double v = *pbrt_float_value(params, "alpha", textures);
  if (v < 1) shape["alpha"] = std::clamp(v, 0.0, 1.0);
}

}  // namespace kasha
