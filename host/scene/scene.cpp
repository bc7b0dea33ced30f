#include "scene/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "core/warning.h"
#include "material/layered_metal.h"
#include "scene/limits.h"
#include "scene/mesh_file.h"
#include "scene/shape_mesh.h"
#include "scene/transform.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

// The materials some shape uses, a mix's two with it (and theirs, in turn), each once.
std::vector<int> Scene::used_materials() const {
  std::vector<bool> seen(materials.size(), false);
  std::vector<int> used, pending;
  for (const ShapeInfo& s : shapes) pending.push_back(s.material);
  while (!pending.empty()) {
    const int m = pending.back();
    pending.pop_back();
    if (seen[m]) continue;
    seen[m] = true;
    used.push_back(m);
    if (materials[m].mix)
      for (int k : materials[m].mix->materials) pending.push_back(k);
  }
  return used;
}

// Only materials that some shape uses count: a declared but unused fluorescent or glossy material
// must not switch on kernels and buffers the scene does not need. A mix's materials count, since
// the kernels meet either at its points.
bool Scene::any_used(const std::function<bool(const Material&)>& has) const {
  for (int m : used_materials())
    if (has(materials[m])) return true;
  return false;
}

bool Scene::mixed() const {
  return any_used([](const Material& m) { return m.kind == MaterialKind::mix; });
}

bool Scene::fluorescent() const {
  const std::vector<bool> used = used_media();
  for (size_t m = 0; m < media.size(); ++m)
    if (used[m] && !media[m].fluorophores.empty()) return true;
  return any_used([](const Material& m) { return m.fluorescent(); });
}
bool Scene::glossy() const {
  return any_used([](const Material& m) { return m.gloss.has_value(); });
}
bool Scene::uses(MaterialKind kind) const {
  return any_used([kind](const Material& m) { return m.kind == kind; });
}
bool Scene::dispersive() const {
  return any_used([](const Material& m) { return m.dispersive(); });
}
bool Scene::rough() const {
  return any_used([](const Material& m) { return m.rough(); });
}
bool Scene::anisotropic() const {
  return any_used([](const Material& m) { return m.rough() && m.roughness.anisotropic(); });
}
bool Scene::coated() const {
  return any_used([](const Material& m) { return m.coat.has_value(); });
}
bool Scene::thin() const {
  return any_used([](const Material& m) { return m.thin; });
}
std::vector<bool> Scene::used_media() const {
  std::vector<bool> used(medium_descs.size(), false);
  const auto use = [&](int m) {
    if (m >= 0) used[m] = true;
  };
  use(camera_medium);
  for (int m : light_media) use(m);
  for (const ShapeInfo& shape : shapes) use(shape.medium.inside), use(shape.medium.outside);
  return used;
}

bool Scene::scattering() const {
  const std::vector<bool> used = used_media();
  for (size_t m = 0; m < media.size(); ++m)
    if (used[m] && media[m].scatters()) return true;
  return false;
}

int Scene::emitting_medium() const {
  const std::vector<bool> used = used_media();
  for (size_t m = 0; m < media.size(); ++m)
    if (used[m] && !media[m].emission.empty()) return static_cast<int>(m);
  return -1;
}

bool Scene::has_media() const {
  if (camera_medium >= 0 || !triangle_media.empty()) return true;
  for (int m : light_media)
    if (m >= 0) return true;
  return false;
}

bool Scene::transmissive() const {
  return any_used([](const Material& m) { return m.transmissive(); });
}
namespace {
// A roughness texture may be smooth (a delta lobe) at some points: such a material may scatter by
// delta too.
bool scatters_by_delta(const Material& m) {
  return (m.specular() && (!m.rough() || m.roughness.may_be_smooth)) ||
         (m.gloss && m.gloss->mirror) || (m.coat && !m.coat->rough());
}
}  // namespace

bool Scene::has_delta_surfaces() const {
  return any_used(scatters_by_delta);
}

bool Scene::mixes_delta() const {
  for (int m : used_materials())
    if (materials[m].mix)
      for (int k : materials[m].mix->materials)
        if (scatters_by_delta(materials[k])) return true;
  return false;
}

bool Scene::textured() const {
  for (int m : used_materials())
    if (material_textures[m].reflectance >= 0 || material_textures[m].fluorescence >= 0 ||
        (materials[m].mix && materials[m].mix->amount_texture >= 0) ||
        (materials[m].rough() && materials[m].roughness.textured()))
      return true;
  return false;
}

bool Scene::normal_mapped() const {
  for (int m : used_materials())
    if (material_textures[m].normal_map >= 0) return true;
  return false;
}

bool Scene::roughness_textured() const {
  return any_used([](const Material& m) { return m.rough() && m.roughness.textured(); });
}

bool Scene::partly_smooth_conductor() const {
  return any_used([](const Material& m) {
    return m.kind == MaterialKind::conductor && m.rough() && m.roughness.may_be_smooth;
  });
}

bool Scene::emission_textured() const {
  for (const Emitter& e : emitters)
    if (e.texture >= 0) return true;
  return false;
}

bool Scene::cut_out() const {
  for (const ShapeInfo& s : shapes)
    if (s.cut_out()) return true;
  return false;
}

bool Scene::has_environment() const {
  for (const Light& l : lights)
    if (l.environment) return true;
  return false;
}

bool Scene::has_light(LightType type) const {
  for (const Light& l : lights)
    if (l.type == type) return true;
  return false;
}

void Scene::bounding_sphere(Eigen::Vector3d& centre, double& radius) const {
  Eigen::AlignedBox3d box;
  const size_t own = instances.empty() ? triangles.size() : size_t(instances.world_triangles);
  for (size_t i = 0; i < own; ++i)
    for (const float* v : {triangles[i].v0, triangles[i].v1, triangles[i].v2})
      box.extend(Eigen::Vector3d(v[0], v[1], v[2]));
  // Each placement's object box, its corners placed: the sphere holds what the kernels meet.
  std::vector<Eigen::AlignedBox3d> objects;
  for (const ObjectRange& r : instances.objects) {
    const std::array<float, 6> b = object_box(triangles, r);
    objects.emplace_back(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d(b[3], b[4], b[5]));
  }
  for (const Placement& p : instances.placements) {
    const Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m(p.world_from_object.data());
    const Eigen::AlignedBox3d& b = objects[p.object];
    if (b.isEmpty()) continue;
    for (int c = 0; c < 8; ++c)
      box.extend(m.leftCols<3>() * b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) +
                 m.col(3));
  }
  centre = box.center();
  radius = std::max(box.diagonal().norm() / 2, 1e-6);
}

size_t Scene::placed_triangles() const {
  if (instances.empty()) return triangles.size();
  size_t n = instances.world_triangles;
  for (const Placement& p : instances.placements) n += instances.objects[p.object].triangle_count;
  return n;
}

// The placement a hit was met in, or null for the scene's own triangles.
static const Placement* hit_placement(const SceneInstances& instances, const KHit& hit) {
  if (hit.instance < 0 || instances.empty()) return nullptr;
  const int own = instances.world_triangles > 0 ? 1 : 0;
  return hit.instance < own ? nullptr : &instances.placements[hit.instance - own];
}

KTriangle Scene::hit_triangle(const KHit& hit) const {
  const Placement* p = hit_placement(instances, hit);
  return p ? placed_triangle(triangles[hit.prim], kernel_instance(*p)) : triangles[hit.prim];
}

Eigen::Vector3d Scene::hit_normal(const KHit& hit, const Eigen::Vector3d& n) const {
  const Placement* p = hit_placement(instances, hit);
  if (!p) return n;
  const Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m(p->world_from_object.data());
  return m.leftCols<3>().inverse().transpose() * n;
}

int Scene::material_index(const std::string& name) const {
  for (size_t i = 0; i < material_descs.size(); ++i)
    if (material_descs[i].name == name) return static_cast<int>(i);
  return -1;
}

double Emitter::integrated_radiance(double bin_nm) const {
  double sum = 0.0;
  for (double v : per_bin) sum += v * bin_nm;
  return sum;
}

double emitted_power(const KTriangle& t, double radiance) {
  Eigen::Vector3d a(t.v0[0], t.v0[1], t.v0[2]), b(t.v1[0], t.v1[1], t.v1[2]),
      c(t.v2[0], t.v2[1], t.v2[2]);
  return 0.5 * (b - a).cross(c - a).norm() * M_PI * radiance;
}

// What the kernels derive from the emitters must fit in float: each binned radiance, each
// emitter's power, and light sampling's density per unit area, π·∫L over the total power (at most
// 1/area for an emitter with power; one of none is never sampled or hit).
static void check_emitters(const Scene& scene) {
  double total_power = 0.0;
  std::vector<double> radiance, power;
  for (const Emitter& e : scene.emitters) {
    for (int i = 0; i < scene.grid.bins; ++i)
      if (!(e.per_bin[i] <= kMaxSpectrumValue)) {
        std::ostringstream msg;
        msg << e.where << ": the radiance of " << e.per_bin[i] << " in the bin " << scene.grid.lo(i)
            << "–" << scene.grid.hi(i) << " nm is beyond 1e30";
        throw Error(msg.str());
      }
    radiance.push_back(e.integrated_radiance(scene.grid.bin_nm));
    double p = 0.0;
    for (int k = 0; k < e.triangle_count; ++k)
      p += emitted_power(scene.triangles[e.first_triangle + k], radiance.back()) * e.texture_mean;
    if (!(p <= kMaxEmitterPower)) {
      std::ostringstream msg;
      msg << e.where << ": the emitted power of " << p << " (π·area·∫L) is beyond 1e35";
      throw Error(msg.str());
    }
    power.push_back(p);
    total_power += p;
  }
  Eigen::Vector3d centre;
  double r;
  scene.bounding_sphere(centre, r);
  for (const Light& l : scene.lights) {
    for (int i = 0; i < scene.grid.bins; ++i)
      if (!(l.per_bin[i] <= kMaxSpectrumValue)) {
        std::ostringstream msg;
        msg << l.where << ": the light's value of " << l.per_bin[i]
            << " (with \"scale\") in the bin " << scene.grid.lo(i) << "–" << scene.grid.hi(i)
            << " nm is beyond 1e30";
        throw Error(msg.str());
      }
    double p = l.power(scene.grid.bin_nm, r);
    if (!(p <= kMaxEmitterPower)) {
      std::ostringstream msg;
      msg << l.where << ": the light's power of " << p << " W is beyond 1e35";
      throw Error(msg.str());
    }
    total_power += p;
  }
  for (size_t i = 0; i < scene.emitters.size(); ++i) {
    if (!(power[i] > 0)) continue;
    double density = M_PI * radiance[i] * scene.emitters[i].texture_mean / total_power;
    if (!(density <= kMaxAreaDensity)) {
      std::ostringstream msg;
      msg << scene.emitters[i].where << ": the emitting area is too small: light sampling's "
          << "density per unit area of " << density << " is beyond 1e30";
      throw Error(msg.str());
    }
  }
}

static Eigen::Vector3d vec(const JsonNode& n) {
  auto a = n.vec3();
  return {a[0], a[1], a[2]};
}

// The set of triangles met so far, by their float vertices: open addressing over 64-bit hashes
// in one flat table, so a million-triangle scene costs one cache miss per triangle (an ordered
// set took over a second there). -0 and +0 compare equal, so they hash alike.
class TriangleKeys {
 public:
  using Key = std::array<float, 9>;
  // The duplicates left out, told once per scene (a published scene has them in dozens of meshes).
  size_t dropped = 0, dropped_shapes = 0;
  std::string first_dropped;
  // Adds `key`; false when an equal key was added before.
  bool insert(const Key& key) {
    if (2 * (keys_.size() + 1) > slots_.size()) grow();
    const std::uint64_t h = hash(key);
    for (size_t i = h & (slots_.size() - 1);; i = (i + 1) & (slots_.size() - 1)) {
      Slot& slot = slots_[i];
      if (slot.index == 0) {
        keys_.push_back(key);
        slot = {h, static_cast<std::uint32_t>(keys_.size())};
        return true;
      }
      if (slot.hash == h && keys_[slot.index - 1] == key) return false;
    }
  }

 private:
  struct Slot {
    std::uint64_t hash = 0;
    std::uint32_t index = 0;  // into keys_, plus one; 0 marks an empty slot
  };
  static std::uint64_t hash(const Key& key) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (float x : key) {
      float y = x + 0.0f;  // -0 -> +0
      std::uint32_t bits;
      std::memcpy(&bits, &y, sizeof bits);
      h = (h ^ bits) * 0xff51afd7ed558ccdull;
      h ^= h >> 32;
    }
    return h;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<size_t>(64, 2 * old.size()), Slot{});
    for (const Slot& s : old) {
      if (s.index == 0) continue;
      size_t i = s.hash & (slots_.size() - 1);
      while (slots_[i].index != 0) i = (i + 1) & (slots_.size() - 1);
      slots_[i] = s;
    }
  }
  std::vector<Key> keys_;
  std::vector<Slot> slots_;  // a power of two, at most half full
};

// Leaves out triangles with the same vertices in the same winding (as the kernels see them, in
// float) as one met before: a coincident twin doubles an emitter's power for light sampling
// while a ray sees one of the two, and rays leaving one copy hit the other. A twin of opposite
// winding stays: it is how a two-sided lamp is made.
static void drop_duplicate_triangles(ShapeMesh& mesh, TriangleKeys& seen, const JsonNode& shape) {
  std::vector<Triangle>& tris = mesh.tris;
  size_t kept = 0;
  for (size_t i = 0; i < tris.size(); ++i) {
    const Triangle& t = tris[i];
    std::array<std::array<float, 3>, 3> v;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) v[k][c] = static_cast<float>(t[k][c]);
    const int first = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
    std::array<float, 9> key;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) key[3 * k + c] = v[(first + k) % 3][c];
    if (seen.insert(key)) {
      mesh.uv[kept] = mesh.uv[i];
      if (!mesh.normals.empty()) mesh.normals[kept] = mesh.normals[i];
      tris[kept++] = t;
    }
  }
  if (kept < tris.size()) {
    if (seen.dropped_shapes++ == 0) seen.first_dropped = shape.where();
    seen.dropped += tris.size() - kept;
  }
  tris.resize(kept);
  mesh.uv.resize(kept);
  if (!mesh.normals.empty()) mesh.normals.resize(kept);
}

static GridRequest parse_grid_request(const JsonNode& node) {
  GridRequest r;
  if (auto lo = node.find("min_nm")) r.min_nm = lo->number_in(1.0, 1e5);
  if (auto hi = node.find("max_nm")) r.max_nm = hi->number_in(1.0, 1e5);
  if (auto bin = node.find("bin_nm")) r.bin_nm = bin->number_in(0.1, 1000.0);
  node.finish();
  double lo = r.min_nm >= 0 ? r.min_nm : kVisibleMinNm,
         hi = r.max_nm >= 0 ? r.max_nm : kVisibleMaxNm;
  if (!(lo < hi)) node.fail("min_nm must be below max_nm");
  if ((hi - lo) / r.bin_nm > 4096) node.fail("more than 4096 bins");
  return r;
}

// {"type": "triangles"}: vertices given inline (pbrt-v4's trianglemesh), flat arrays of
// "positions" (x y z …), "indices" (three a triangle), and optional "normals" and "uvs" per vertex.
static ShapeMesh indexed_triangles(const JsonNode& shape) {
  const JsonNode pos = shape.at("positions");
  const std::vector<double> p = pos.numbers();
  if (p.empty() || p.size() % 3 != 0) pos.fail("expected x, y, z for each vertex");
  const size_t vertices = p.size() / 3;
  const JsonNode idx = shape.at("indices");
  const std::vector<double> index = idx.numbers();
  if (index.empty() || index.size() % 3 != 0) idx.fail("expected three indices a triangle");
  for (size_t i = 0; i < index.size(); ++i)
    if (!(index[i] >= 0 && index[i] < double(vertices) && index[i] == std::floor(index[i])))
      idx[i].fail("names no vertex (" + std::to_string(vertices) + " vertices)");
  std::vector<double> n, uv;
  if (auto normals = shape.find("normals")) {
    n = normals->numbers();
    if (n.size() != p.size()) normals->fail("expected one normal for each vertex");
  }
  if (auto uvs = shape.find("uvs")) {
    uv = uvs->numbers();
    if (uv.size() != 2 * vertices) uvs->fail("expected u, v for each vertex");
  }
  ShapeMesh mesh;
  const auto at = [&](size_t t, int k) { return static_cast<size_t>(index[3 * t + k]); };
  for (size_t t = 0; t < index.size() / 3; ++t) {
    Triangle tri;
    TriangleUv tuv;
    TriangleNormals tn;
    bool shaded = !n.empty();
    for (int k = 0; k < 3; ++k) {
      const size_t v = at(t, k);
      tri[k] = {p[3 * v], p[3 * v + 1], p[3 * v + 2]};
      // pbrt-v4's (0, 0), (1, 0), (1, 1) without "uvs".
      tuv[k] =
          uv.empty() ? Eigen::Vector2d(k > 0, k > 1) : Eigen::Vector2d(uv[2 * v], uv[2 * v + 1]);
      if (shaded) {
        const Eigen::Vector3d nv(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
        shaded = nv.norm() > 0 && nv.allFinite();
        tn[k] = shaded ? nv.normalized() : nv;
      }
    }
    if (!n.empty() && !shaded) {  // a zero normal: flat, as in an OBJ file
      const Eigen::Vector3d g = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
      const Eigen::Vector3d flat = g.norm() > 0 ? g.normalized() : Eigen::Vector3d(0, 0, 1);
      tn = {flat, flat, flat};
    }
    mesh.tris.push_back(tri);
    mesh.uv.push_back(tuv);
    if (!n.empty()) mesh.normals.push_back(tn);
  }
  return mesh;
}

// Triangles of one shape, in world space, front sides as the shape asks.
static ShapeMesh shape_triangles(const JsonNode& shape, const std::string& type) {
  ShapeMesh tris;
  if (type == "obj") {
    std::filesystem::path file = shape.at("file").file_path();
    tris = obj_triangles(file.string());
  } else if (type == "mesh") {
    std::filesystem::path file = shape.at("file").file_path();
    tris = mesh_file_triangles(file.string());
  } else if (type == "quad") {
    Eigen::Vector3d u = vec(shape.at("u")), v = vec(shape.at("v"));
    if (u.cross(v).norm() == 0) shape.fail("quad edges \"u\" and \"v\" are parallel or zero");
    tris = quad_triangles(vec(shape.at("corner")), u, v);
  } else if (type == "box") {
    Eigen::Vector3d lo = vec(shape.at("min")), hi = vec(shape.at("max"));
    if (!(lo.array() < hi.array()).all())
      shape.fail("box \"min\" must be below \"max\" on every axis");
    tris = box_triangles(lo, hi);
  } else if (type == "sphere") {
    double r = shape.at("radius").number();
    if (!(r > 0)) shape.fail("sphere radius must be positive");
    int segments = 64;
    if (auto s = shape.find("segments")) segments = s->integer_in(3, 4096);
    tris = sphere_triangles(vec(shape.at("center")), r, segments);
  } else if (type == "triangles") {
    tris = indexed_triangles(shape);
  } else {
    shape.at("type").fail("unknown shape type \"" + type +
                          "\" (obj, mesh, triangles, quad, box, sphere)");
  }
  if (auto t = shape.find("transform")) transform_triangles(tris, parse_transform(*t));
  if (auto inward = shape.find("inward")) {
    if (type != "box" && type != "sphere")
      inward->fail("\"inward\" applies to closed shapes (box, sphere)");
    if (inward->boolean()) flip_triangles(tris);
  }
  if (auto reverse = shape.find("reverse_orientation"))
    if (reverse->boolean()) flip_triangles(tris);
  return tris;
}

// An emitting shape's sphere light: a "sphere", or "triangles" whose "sphere" names the sphere
// they tessellate (pbrt-v4's full sphere), where the shape's "transform" keeps it one.
static std::optional<SphereBound> shape_sphere_light(const JsonNode& shape, const std::string& type,
                                                     const ShapeMesh& mesh) {
  SphereBound own;
  if (type == "sphere") {
    own = {vec(shape.at("center")), shape.at("radius").number()};
  } else if (auto s = shape.find("sphere")) {
    if (type != "triangles") s->fail("\"sphere\" applies to \"triangles\"");
    own = {vec(s->at("center")), s->at("radius").number()};
    s->finish();
  } else {
    return std::nullopt;
  }
  Eigen::Affine3d placed = Eigen::Affine3d::Identity();
  if (auto t = shape.find("transform")) placed = parse_transform(*t);
  return tessellated_sphere(mesh, own, placed);
}

// The emission of the shapes marked "lamp": true — the chosen one of the scene's named "lamps",
// each parsed (so a bad one is reported whichever is on). Empty without "lamps".
struct LampChoice {
  SpectrumPtr spectrum;
  std::string where;
};

static LampChoice choose_lamp(const JsonNode& root, const std::string& requested, Scene& scene) {
  auto lamps = root.find("lamps");
  if (!lamps) {
    if (root.has("lamp")) root.at("lamp").fail("\"lamp\" needs the scene's \"lamps\"");
    if (!requested.empty())
      throw Error("--lamp " + requested + ": " + scene.file + " has no \"lamps\" to switch");
    return {};
  }
  if (!lamps->is_object()) lamps->fail("expected an object of named emission spectra");
  std::map<std::string, LampChoice> parsed;
  for (const std::string& name : lamps->keys()) {
    JsonNode n = lamps->at(name);
    parsed[name] = {parse_spectrum(n), n.where()};
    scene.lamp_names.push_back(name);
  }
  if (parsed.empty()) lamps->fail("no lamps");
  std::string known;
  for (const std::string& name : scene.lamp_names) known += (known.empty() ? "" : ", ") + name;
  JsonNode chosen = root.at("lamp");
  scene.lamp = chosen.string();
  if (!parsed.count(scene.lamp))
    chosen.fail("no lamp named \"" + scene.lamp + "\" (" + known + ")");
  if (!requested.empty()) {
    if (!parsed.count(requested))
      throw Error("--lamp " + requested + ": " + scene.file + " has no lamp of that name (" +
                  known + ")");
    scene.lamp = requested;
  }
  return parsed.at(scene.lamp);
}

// The scene's "materials": each inline, or {"file": ...} relative to the scene's folder.
// An emission texture's mean over its image or its squares (light sampling weighs the emitter by
// it); a checkerboard's values must be numbers ≥ 0 there.
static double texture_mean(const Texture& t, const JsonNode& where) {
  if (t.program())
    where.fail(
        "an emission texture is an image or a (u, v) checkerboard of numbers, not a "
        "texture of textures");
  if (t.type == TextureType::checkerboard) {
    if (!(t.even_value >= 0 && t.odd_value >= 0))
      where.fail("an emission texture's checkerboard needs numbers ≥ 0 for \"even\" and \"odd\"");
    return (t.even_value + t.odd_value) / 2;
  }
  double sum = 0;
  for (float v : t.image.rgb) sum += v;
  return t.image.rgb.empty() ? 0 : sum / t.image.rgb.size();
}

// A material entry's "textures": {"reflectance": NAME, "fluorescence": NAME}, each one of the
// scene's "textures".
static MaterialTextures parse_material_textures(const JsonNode& m, const Scene& scene) {
  MaterialTextures mt;
  auto textures = m.find("textures");
  if (!textures) return mt;
  if (!textures->is_object())
    textures->fail("expected {\"reflectance\": NAME, \"fluorescence\": NAME}");
  mt.where = textures->where();
  auto lookup = [&](const char* key, int& out) {
    if (auto n = textures->find(key)) {
      const std::string name = n->string();
      for (size_t i = 0; i < scene.textures.size(); ++i)
        if (scene.textures[i].name == name) out = static_cast<int>(i);
      if (out < 0) n->fail("no texture named \"" + name + "\" in the scene's \"textures\"");
    }
  };
  lookup("reflectance", mt.reflectance);
  lookup("fluorescence", mt.fluorescence);
  textures->finish();
  return mt;
}

// What a material's textures apply to must be there: a passive part to print on, a fluorescent
// part to scale; scaled excitation stays in [0, 1] (a concentration) and printed reflectance
// within the material's own.
static void check_material_textures(const Scene& scene) {
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialTextures& mt = scene.material_textures[i];
    const Material& m = scene.materials[i];
    // pbrt-v4's mix has none: the material it picks shades with its own.
    if (mt.normal_map >= 0 && m.mix)
      throw Error(mt.normal_map_where + ": a mix's normal maps are its materials' own");
    if (mt.reflectance < 0 && mt.fluorescence < 0) continue;
    if (m.mix) throw Error(mt.where + ": a mix's textures are its materials' own");
    if (m.kind != MaterialKind::measured)
      throw Error(mt.where + ": textures apply to a measured material's Lambert parts, not to a " +
                  "dielectric or conductor");
    if (mt.reflectance >= 0 && m.rho.empty())
      throw Error(mt.where + ": a reflectance texture multiplies the material's passive " +
                  "reflectance, and \"" + scene.material_descs[i].name + "\" has none");
    if (mt.fluorescence >= 0 && !m.fluorescent())
      throw Error(mt.where + ": a fluorescence texture scales the material's excitation, and \"" +
                  scene.material_descs[i].name + "\" does not fluoresce");
    if (mt.fluorescence >= 0) {
      const Texture& t = scene.textures[mt.fluorescence];
      if (t.type == TextureType::checkerboard && !t.program() &&
          !(t.even_value >= 0 && t.even_value <= 1 && t.odd_value >= 0 && t.odd_value <= 1))
        throw Error(t.where + ": a fluorescence texture's \"even\" and \"odd\" are " +
                    "concentrations: numbers in [0, 1]");
    }
    if (mt.reflectance >= 0) {
      const Texture& t = scene.textures[mt.reflectance];
      // A program's value is clamped to [0, 1] where it is looked up, as pbrt-v4 clamps.
      if (t.type == TextureType::checkerboard && !t.program())
        for (const SpectrumPtr& v : {t.even, t.odd})
          for (double x : scene.grid.resample(*v))
            if (!(x <= 1))
              throw Error(t.where + ": a reflectance texture's values multiply a reflectance: " +
                          "at most 1 in every bin");
    }
  }
}

// A mix may name mixes, at most kMaxMixDepth deep (the kernels resolve that many in turn); one
// that names itself, in turn, never ends and is refused the same way.
static void check_mix_nesting(const Scene& scene, int m, int depth) {
  const MaterialDesc& d = scene.material_descs[m];
  if (!d.mix) return;
  if (depth >= kMaxMixDepth)
    throw Error(d.mix->where + ": mixes nest deeper than " + std::to_string(kMaxMixDepth) +
                " (or a mix names itself in turn)");
  for (int k : d.mix->materials) check_mix_nesting(scene, k, depth + 1);
}

// A texture of numbers in [0, 1] where the scene takes a share or a roughness: a checkerboard of
// values must have its two there (other textures are clamped to it where they are looked up).
static void check_unit_texture(const Texture& t, const std::string& use) {
  if (t.type == TextureType::checkerboard && !t.program() &&
      !(t.even_value >= 0 && t.even_value <= 1 && t.odd_value >= 0 && t.odd_value <= 1))
    throw Error(t.where + ": " + use + " texture's \"even\" and \"odd\" are numbers in [0, 1]");
}

// Whether a roughness texture may give alpha below 1e-3 (smooth) somewhere: a (u, v) checkerboard
// or an image (its texels' mean of R, G and B, bilinear between them) whose every value is above
// is not; a texture of textures may be.
static bool may_be_smooth(const Texture& t, bool remap) {
  const double least = (remap ? 1e-6 : 1e-3) * 1.01;  // a little above: float lookups
  if (t.program()) return true;
  if (t.type == TextureType::checkerboard) return std::min(t.even_value, t.odd_value) < least;
  if (t.wrap == TextureWrap::black) return true;
  const std::vector<float>& c = t.image.rgb;
  for (size_t p = 0; p + 2 < c.size(); p += 3)
    if ((c[p] + c[p + 1] + c[p + 2]) / 3 < least) return true;
  return false;
}

// A rough dielectric's or conductor's roughness textures as the scene's indices; a point is
// smooth only where both axes are.
static void resolve_roughness_textures(Scene& scene) {
  for (MaterialDesc& d : scene.material_descs) {
    Roughness& r = d.roughness;
    if (!r.textured()) continue;
    r.may_be_smooth = true;
    for (int axis = 0; axis < 2; ++axis) {
      if (r.texture_name[axis].empty()) {
        r.may_be_smooth = r.may_be_smooth && (axis == 0 ? r.alpha_x : r.alpha_y) < 1e-3;
        continue;
      }
      for (size_t i = 0; i < scene.textures.size(); ++i)
        if (scene.textures[i].name == r.texture_name[axis]) r.texture[axis] = static_cast<int>(i);
      if (r.texture[axis] < 0)
        throw Error(r.where[axis] + ": no texture named \"" + printable(r.texture_name[axis]) +
                    "\" in the scene's \"textures\"");
      const Texture& t = scene.textures[r.texture[axis]];
      check_unit_texture(t, "a roughness");
      r.may_be_smooth = r.may_be_smooth && may_be_smooth(t, r.remap);
    }
  }
}

// A coat's roughness texture read as its mean (the coat's tables take one roughness per
// material), with a warning: an image's texels (their mean of R, G and B, clamped to [0, 1]) or a
// checkerboard's two numbers; a texture of textures is refused.
static void resolve_coat_roughness(Scene& scene) {
  for (MaterialDesc& d : scene.material_descs) {
    if (!d.coat || d.coat->alpha_texture.empty()) continue;
    CoatDesc& c = *d.coat;
    const Texture* t = nullptr;
    for (const Texture& candidate : scene.textures)
      if (candidate.name == c.alpha_texture) t = &candidate;
    if (!t)
      throw Error(c.alpha_where + ": no texture named \"" + printable(c.alpha_texture) +
                  "\" in the scene's \"textures\"");
    check_unit_texture(*t, "a roughness");
    if (t->program())
      throw Error(c.alpha_where +
                  ": a coat takes one roughness: its texture must be an image or "
                  "a checkerboard of numbers, whose mean kasha takes");
    double mean = 0;
    if (t->type == TextureType::checkerboard) {
      mean = (t->even_value + t->odd_value) / 2;
    } else {
      const std::vector<float>& rgb = t->image.rgb;
      for (size_t p = 0; p + 2 < rgb.size(); p += 3)
        mean += std::clamp((rgb[p] + rgb[p + 1] + rgb[p + 2]) / 3.0, 0.0, 1.0);
      mean /= std::max<size_t>(1, rgb.size() / 3);
    }
    c.alpha = c.alpha_remap ? std::sqrt(mean) : mean;
    char v[96];
    std::snprintf(v, sizeof v, "%.4g (GGX alpha %.4g)", mean, c.alpha);
    warn(c.alpha_where +
         ": a coat takes one roughness in kasha: its texture is read as its mean, " + v);
  }
}

// A mix's material and texture names as the scene's indices.
static void resolve_mixes(Scene& scene) {
  for (MaterialDesc& d : scene.material_descs) {
    if (!d.mix) continue;
    MaterialMix& mix = *d.mix;
    for (int k = 0; k < 2; ++k) {
      mix.materials[k] = scene.material_index(mix.names[k]);
      if (mix.materials[k] < 0)
        throw Error(mix.where + ": no material named \"" + printable(mix.names[k]) + "\"");
    }
    if (mix.amount_texture_name.empty()) continue;
    for (size_t i = 0; i < scene.textures.size(); ++i)
      if (scene.textures[i].name == mix.amount_texture_name)
        mix.amount_texture = static_cast<int>(i);
    if (mix.amount_texture < 0)
      throw Error(mix.where + ": no texture named \"" + printable(mix.amount_texture_name) +
                  "\" in the scene's \"textures\"");
    check_unit_texture(scene.textures[mix.amount_texture], "a mix's amount");
  }
  for (size_t m = 0; m < scene.material_descs.size(); ++m)
    check_mix_nesting(scene, static_cast<int>(m), 0);
}

// A rough layered metal (a conductor under a coat, either rough) becomes a mix of its two parts
// (material/layered_metal.h): the metal seen through the coat, and a coated Lambert part that
// carries the coat's reflection. Their spectra and shares need the grid: finish_layered_metals.
static void split_layered_metals(Scene& scene) {
  const size_t count = scene.material_descs.size();
  for (size_t i = 0; i < count; ++i) {
    const MaterialDesc d = scene.material_descs[i];
    if (d.kind != MaterialKind::conductor || !d.coat || !(d.coat->rough() || d.roughness.rough()))
      continue;
    MaterialDesc metal = d, layer;
    metal.name = d.name + " (its metal)";
    metal.under_coat = true;
    metal.layered_alpha = std::sqrt(d.roughness.alpha_x * d.roughness.alpha_y);
    metal.roughness.alpha_x = layered_metal_alpha(*d.coat, d.roughness.alpha_x);
    metal.roughness.alpha_y = layered_metal_alpha(*d.coat, d.roughness.alpha_y);
    layer.name = d.name + " (its layer)";
    layer.where = d.where;
    layer.coat = d.coat;
    MaterialMix mix;
    mix.names[0] = metal.name;
    mix.names[1] = layer.name;
    mix.materials[0] = static_cast<int>(scene.material_descs.size());
    mix.materials[1] = mix.materials[0] + 1;
    mix.where = d.where;
    MaterialDesc& parent = scene.material_descs[i];
    parent.kind = MaterialKind::mix;
    parent.mix = mix;
    parent.coat.reset();
    parent.roughness = Roughness{};
    // The parts carry the normal map (a mix's are its materials' own).
    MaterialTextures parts;
    parts.normal_map = scene.material_textures[i].normal_map;
    parts.normal_map_where = scene.material_textures[i].normal_map_where;
    scene.material_textures[i].normal_map = -1;
    scene.material_descs.push_back(metal);
    scene.material_descs.push_back(layer);
    scene.material_textures.push_back(parts);
    scene.material_textures.push_back(parts);
  }
  // A layered metal inside a mix is one mix deeper than it was written.
  if (scene.material_descs.size() > count)
    for (size_t m = 0; m < count; ++m) check_mix_nesting(scene, static_cast<int>(m), 0);
}

// The parts' spectra and shares on the grid (material/layered_metal.h), for the used ones (the
// walk is the cost).
static void finish_layered_metals(const std::vector<bool>& material_used, Scene& scene) {
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    Material& m = scene.materials[i];
    if (!m.mix || !scene.materials[m.mix->materials[0]].under_coat) continue;
    if (!material_used[m.mix->materials[0]]) continue;
    Material& metal = scene.materials[m.mix->materials[0]];
    Material& layer = scene.materials[m.mix->materials[1]];
    const MaterialDesc& given = scene.material_descs[m.mix->materials[0]];
    const double alpha = std::sqrt(metal.roughness.alpha_x * metal.roughness.alpha_y);
    const LayeredMetalParts parts =
        layered_metal_parts(*metal.coat, given.layered_alpha, alpha, metal.eta_c, metal.k_c);
    layer.rho = parts.scattered;
    layer.lambert_transmission = parts.shape;
    layer.layer_scale = 1 / parts.lambert_share;
    metal.layer_scale = parts.once_scale / (1 - parts.lambert_share);
    m.mix->amount = parts.lambert_share;
    scene.material_descs[i].mix->amount = parts.lambert_share;
  }
}

static void parse_materials(const JsonNode& materials, Scene& scene) {
  for (const std::string& name : materials.keys()) {
    JsonNode m = materials.at(name);
    if (!m.is_object()) m.fail("expected a material object or {\"file\": ...}");
    scene.material_textures.push_back(parse_material_textures(m, scene));
    if (auto normal_map = m.find("normal_map")) {
      scene.material_textures.back().normal_map = read_normal_map(*normal_map, scene.normal_maps);
      scene.material_textures.back().normal_map_where = normal_map->where();
    }
    if (auto file = m.find("file")) {
      std::filesystem::path p = file->file_path();
      auto coat = m.find("coat");  // a measured material under a lacquer
      m.finish();
      scene.material_descs.push_back(load_material_file(p.string(), name));
      if (coat) apply_coat(scene.material_descs.back(), *coat);
    } else {
      scene.material_descs.push_back(parse_material(m, name));
    }
  }
  resolve_mixes(scene);
  resolve_roughness_textures(scene);
  resolve_coat_roughness(scene);
  split_layered_metals(scene);
}

// Vertices must be finite and well inside float range after transforms: squared distances of
// them must not overflow, and Embree asserts on non-finite bounds.
static void check_vertices(const std::vector<Triangle>& tris, const JsonNode& shape) {
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(t[k][c]) <= kMaxCoordinate)) {
          char v[128];
          std::snprintf(v, sizeof v, "(%g, %g, %g)", t[k][0], t[k][1], t[k][2]);
          shape.fail(std::string("a vertex at ") + v + " is not finite or beyond ±1e18");
        }
}

// A shape's triangles in kernel layout, after the scene's.
// The geometric normal of a kernel triangle at each vertex: shading normals for a triangle whose
// shape has none, in a scene where another shape has them.
static TriangleNormals flat_normals(const KTriangle& k) {
  Eigen::Vector3d v0(k.v0[0], k.v0[1], k.v0[2]), v1(k.v1[0], k.v1[1], k.v1[2]),
      v2(k.v2[0], k.v2[1], k.v2[2]);
  const Eigen::Vector3d g = (v1 - v0).cross(v2 - v0).normalized();
  return {g, g, g};
}

static void append_triangles(const ShapeMesh& mesh, int material, int emitter, Scene& scene) {
  scene.uvs.insert(scene.uvs.end(), mesh.uv.begin(), mesh.uv.end());
  // Shading normals are kept for every triangle once some shape has them.
  if (!mesh.normals.empty() && scene.normals.empty())
    for (const KTriangle& k : scene.triangles) scene.normals.push_back(flat_normals(k));
  const bool normals = !mesh.normals.empty() || !scene.normals.empty();
  for (size_t i = 0; i < mesh.tris.size(); ++i) {
    const Triangle& t = mesh.tris[i];
    KTriangle k{};
    for (int c = 0; c < 3; ++c) {
      k.v0[c] = static_cast<float>(t[0][c]);
      k.v1[c] = static_cast<float>(t[1][c]);
      k.v2[c] = static_cast<float>(t[2][c]);
    }
    k.material = material;
    k.emitter = emitter;
    k.prim = static_cast<int>(scene.triangles.size());
    if (normals) scene.normals.push_back(mesh.normals.empty() ? flat_normals(k) : mesh.normals[i]);
    scene.triangles.push_back(k);
  }
}

// The scene's JSON: the file itself, or a pbrt-v4 scene read into that form; --material's
// replacements applied.
static JsonNode read_scene_document(const std::string& path,
                                    const std::vector<MaterialOverride>& materials) {
  if (is_pbrt_scene(path)) {
    auto sources = std::make_shared<JsonSourceMap>();
    nlohmann::json scene = import_pbrt_scene(path, materials, sources.get());
    return JsonNode::from_json(std::move(scene), path, sources);
  }
  JsonNode checked = JsonNode::load_file(path);  // strict: a key twice, bad syntax
  if (materials.empty()) return checked;
  nlohmann::json document = nlohmann::json::parse(read_input_file(path, kMaxTextInputBytes));
  for (const MaterialOverride& m : materials) {
    if (!document.is_object() || !document.contains("materials") ||
        !document["materials"].is_object() || !document["materials"].contains(m.name))
      throw Error("--material " + printable(m.name) + "=" + printable(m.file) + ": " +
                  printable(path) + " has no material named \"" + printable(m.name) + "\"");
    document["materials"][m.name] = {
        {"file", std::filesystem::absolute(m.file).lexically_normal().string()}};
  }
  return JsonNode::from_json(std::move(document), path);
}

static void parse_textures(const JsonNode& root, Scene& scene) {
  if (auto textures = root.find("textures")) {
    if (!textures->is_object()) textures->fail("expected an object of named textures");
    for (const std::string& name : textures->keys())
      scene.textures.push_back(parse_texture(textures->at(name), name));
    resolve_texture_inputs(scene.textures);
  }
}

// The scene's "media" (docs/media.md), and the camera's.
static void parse_media(const JsonNode& root, const JsonNode& camera, Scene& scene) {
  if (auto media = root.find("media")) {
    if (!media->is_object()) media->fail("expected an object of named media");
    for (const std::string& name : media->keys()) {
      if (name.empty()) media->fail("a medium's name must not be empty (\"\" is vacuum)");
      scene.medium_descs.push_back(parse_medium(media->at(name), name));
    }
  }
  if (auto m = camera.find("medium")) scene.camera_medium = medium_index(*m, scene.medium_descs);
}

static void parse_lights(const JsonNode& root, Scene& scene) {
  if (auto lights = root.find("lights")) {
    if (!lights->is_array()) lights->fail("expected an array of lights");
    for (size_t i = 0; i < lights->size(); ++i) {
      const JsonNode l = (*lights)[i];
      std::optional<JsonNode> medium = l.is_object() ? l.find("medium") : std::nullopt;
      scene.light_media.push_back(medium ? medium_index(*medium, scene.medium_descs) : -1);
      scene.lights.push_back(parse_light(l));
      const LightType type = scene.lights.back().type;
      if (scene.light_media.back() >= 0 && type != LightType::point && type != LightType::spot)
        medium->fail("a distant or infinite light is outside the scene, in no medium");
    }
  }
}

// What the shapes use of what the scene declares: the materials (by index) and the lamp.
struct ShapeUses {
  std::vector<bool> materials;
  bool lamp = false;
};

// An emitter's "emission_texture": the texture it names, and its mean.
static void parse_emission_texture(const JsonNode& tex, const Scene& scene, Emitter& e) {
  const std::string name = tex.string();
  for (size_t i = 0; i < scene.textures.size(); ++i)
    if (scene.textures[i].name == name) e.texture = static_cast<int>(i);
  if (e.texture < 0) tex.fail("no texture named \"" + name + "\" in the scene's \"textures\"");
  e.texture_mean = texture_mean(scene.textures[e.texture], tex);
}

// The emitter of a shape that gives "emission" or "lamp" (the index of the one added to the
// scene), else -1. `triangles`: how many the shape adds.
static int parse_shape_emitter(const JsonNode& shape, size_t triangles, const LampChoice& lamp_on,
                               ShapeUses& uses, Scene& scene) {
  auto emission = shape.find("emission");
  bool emits_lamp = false;
  if (auto is_lamp = shape.find("lamp")) {
    if (emission) is_lamp->fail("a shape takes \"emission\" or \"lamp\", not both");
    if (!lamp_on.spectrum) is_lamp->fail("\"lamp\" needs the scene's \"lamps\"");
    if (!is_lamp->boolean())
      is_lamp->fail("expected true (a shape that emits the lamp that is on)");
    emits_lamp = uses.lamp = true;
  }
  if (shape.has("emission_texture") && !emission && !emits_lamp)
    shape.at("emission_texture")
        .fail("an emission texture needs the shape's \"emission\" or \"lamp\"");
  if (!emission && !emits_lamp) return -1;
  Emitter e;
  if (emission) {
    e.where = emission->where();
    e.radiance = parse_spectrum(*emission);
  } else {
    e.where = lamp_on.where;
    e.radiance = lamp_on.spectrum;
  }
  e.first_triangle = static_cast<int>(scene.triangles.size());
  e.triangle_count = static_cast<int>(triangles);
  if (auto tex = shape.find("emission_texture")) parse_emission_texture(*tex, scene, e);
  scene.emitters.push_back(e);
  return static_cast<int>(scene.emitters.size()) - 1;
}

// A shape's "alpha": a number in [0, 1], or the name of one of the scene's textures whose value
// (a scalar, as a concentration's) is the alpha at each point.
static void parse_shape_alpha(const JsonNode& alpha, const Scene& scene, ShapeInfo& info) {
  if (alpha.is_string()) {
    const std::string name = alpha.string();
    for (size_t i = 0; i < scene.textures.size(); ++i)
      if (scene.textures[i].name == name) info.alpha_texture = static_cast<int>(i);
    if (info.alpha_texture < 0)
      alpha.fail("no texture named \"" + name + "\" in the scene's \"textures\"");
    return;
  }
  info.alpha = alpha.number_in(0, 1);
}

// A used mix's materials, and in turn theirs, are used.
static void mark_mix_used(const Scene& scene, int m, ShapeUses& uses) {
  uses.materials[m] = true;
  if (const auto& mix = scene.material_descs[m].mix)
    for (int k : mix->materials) mark_mix_used(scene, k, uses);
}

static int shape_material(const JsonNode& shape, ShapeUses& uses, Scene& scene);

// One shape of the scene's "shapes" (or of an object's, `placed` by its one instance when it has
// one): its triangles, material and emission added to the scene.
static void parse_shape(const JsonNode& shape, const LampChoice& lamp_on,
                        TriangleKeys& seen_triangles, ShapeUses& uses, Scene& scene,
                        bool in_object = false, const Eigen::Affine3d* placed = nullptr) {
  if (!shape.is_object()) shape.fail("expected a shape object");
  for (const char* key : {"emission", "lamp"})
    if (in_object && shape.has(key))
      shape.at(key).fail(
          "a shape of an object does not emit (an instance is not a light): give the shape "
          "in the scene's \"shapes\"");
  std::string type = shape.at("type").string();
  const int material = shape_material(shape, uses, scene);
  ShapeMesh mesh = shape_triangles(shape, type);
  if (placed) transform_triangles(mesh, *placed);
  check_vertices(mesh.tris, shape);
  drop_duplicate_triangles(mesh, seen_triangles, shape);
  const int emitter = parse_shape_emitter(shape, mesh.tris.size(), lamp_on, uses, scene);
  bool inward = false;
  if (auto in = shape.find("inward")) inward = in->boolean();
  ShapeInfo info;
  info.type = type;
  info.inward = inward;
  info.material = material;
  info.emitter = emitter;
  info.first_triangle = static_cast<int>(scene.triangles.size());
  info.triangle_count = static_cast<int>(mesh.tris.size());
  if (auto alpha = shape.find("alpha")) parse_shape_alpha(*alpha, scene, info);
  if (auto medium = shape.find("medium")) info.medium = parse_medium_interface(*medium, scene.medium_descs);
  if (scene.material_descs[material].kind == MaterialKind::interface) {
    if (emitter >= 0) shape.at("interface").fail("an interface has no surface to emit from");
    if (!info.medium.transition())
      shape.at("interface").fail("an interface bounds media: give its \"medium\" two different sides");
  }
  // Read whether or not it emits ("sphere" is a key like any other).
  std::optional<SphereBound> sphere = shape_sphere_light(shape, type, mesh);
  if (emitter >= 0 && !info.cut_out()) info.sphere_light = sphere;
  shape.finish();
  scene.shapes.push_back(info);
  const size_t before = scene.triangles.size();
  append_triangles(mesh, material, emitter, scene);
  // Kept per triangle from the first boundary on (the triangles before it bound nothing).
  if (info.medium.transition() || !scene.triangle_media.empty()) {
    scene.triangle_media.resize(before);
    scene.triangle_media.resize(scene.triangles.size(), info.medium);
  }
}

// A shape's material: the one its "material" names, or, for "interface": true, the scene's one
// interface material (added when a shape first asks for it).
static int shape_material(const JsonNode& shape, ShapeUses& uses, Scene& scene) {
  if (auto in = shape.find("interface")) {
    if (!in->boolean()) in->fail("expected true (a shape that only bounds media), or leave it out");
    if (shape.has("material")) in->fail("an interface has no material: give one or the other");
    int m = scene.material_index(kInterfaceMaterial);
    if (m < 0) {
      MaterialDesc d;
      d.name = kInterfaceMaterial;
      d.where = in->where();
      d.kind = MaterialKind::interface;
      scene.material_descs.push_back(d);
      scene.material_textures.emplace_back();
      uses.materials.push_back(false);
      m = static_cast<int>(scene.material_descs.size()) - 1;
    }
    uses.materials[m] = true;
    return m;
  }
  const std::string material_name = shape.at("material").string();
  const int material = scene.material_index(material_name);
  if (material < 0) shape.at("material").fail("no material named \"" + material_name + "\"");
  uses.materials[material] = true;
  return material;
}

// The grid covers what the emitters and the materials in use need; materials, emitters and
// lights are then sampled on it.
static void discretize(const GridRequest& request, const std::vector<bool>& material_used,
                       Scene& scene) {
  std::vector<SpectralSupport> emitting, exciting;
  for (const Emitter& e : scene.emitters) emitting.push_back(e.radiance->support());
  for (const Light& l : scene.lights) emitting.push_back(l.spectrum->support());
  for (size_t m = 0; m < scene.material_descs.size(); ++m)
    if (material_used[m] && scene.material_descs[m].excitation)
      exciting.push_back(scene.material_descs[m].excitation->support());
  // A used medium's fluorophores excite as a material's fluorescent part does; its emission
  // emits as an emitter does.
  const std::vector<bool> media_used = scene.used_media();
  for (size_t m = 0; m < scene.medium_descs.size(); ++m) {
    if (!media_used[m]) continue;
    for (const FluorophoreDesc& f : scene.medium_descs[m].fluorophores)
      exciting.push_back(f.absorption->support());
    if (scene.medium_descs[m].emission)
      emitting.push_back(scene.medium_descs[m].emission->support());
  }
  scene.grid = choose_grid(request, emitting, exciting);

  for (const MaterialDesc& d : scene.material_descs)
    scene.materials.push_back(discretize_material(d, scene.grid));
  finish_layered_metals(material_used, scene);
  for (Emitter& e : scene.emitters) e.per_bin = scene.grid.resample(*e.radiance);
  for (Light& l : scene.lights) {
    l.per_bin = scene.grid.resample(*l.spectrum);
    for (double& v : l.per_bin) v *= l.scale;
    if (l.environment)
      l.environment_data = std::make_shared<const EnvironmentData>(
          environment_data(*l.environment, l.per_bin, scene.grid));
  }
}

// The media on the scene's grid.
static void discretize_media(Scene& scene) {
  for (const MediumDesc& d : scene.medium_descs) scene.media.push_back(discretize_medium(d, scene.grid));
}

// An instance's placed object must stay within the coordinates every vertex keeps to.
static void check_placed_box(const Scene& scene, const Placement& p, const JsonNode& where) {
  const ObjectRange& r = scene.instances.objects[p.object];
  const Eigen::Matrix<double, 3, 4, Eigen::RowMajor> m(p.world_from_object.data());
  for (int i = r.first_triangle; i < r.first_triangle + r.triangle_count; ++i)
    for (const float* v : {scene.triangles[i].v0, scene.triangles[i].v1, scene.triangles[i].v2}) {
      const Eigen::Vector3d w = m.leftCols<3>() * Eigen::Vector3d(v[0], v[1], v[2]) + m.col(3);
      if (!(w.cwiseAbs().maxCoeff() <= kMaxCoordinate))
        where.fail("the object placed here has a vertex that is not finite or beyond ±1e18");
    }
}

// "objects" and "instances" (docs/formats.md#instances), after the scene's own shapes: an object
// placed once joins the scene's own triangles; one placed more often is stored once, after them,
// with each placement kept for the two-level BVH. An object placed nowhere adds nothing.
static void parse_instances(const JsonNode& root, const LampChoice& lamp_on,
                            TriangleKeys& seen_triangles, ShapeUses& uses, Scene& scene) {
  auto objects = root.find("objects");
  auto instances = root.find("instances");
  if (instances && !objects) instances->fail("\"instances\" place the scene's \"objects\"");
  if (!objects) return;
  if (!objects->is_object()) objects->fail("expected an object of named shape arrays");
  const std::vector<std::string> names = objects->keys();
  std::vector<std::vector<Eigen::Affine3d>> placed(names.size());
  std::vector<std::vector<JsonNode>> where(names.size());
  for (size_t i = 0; instances && i < instances->size(); ++i) {
    JsonNode in = (*instances)[i];
    if (!in.is_object()) in.fail("expected {\"object\": NAME, \"transform\": ...}");
    const std::string name = in.at("object").string();
    const auto k = std::find(names.begin(), names.end(), name) - names.begin();
    if (k == long(names.size())) in.at("object").fail("no object named \"" + name + "\"");
    placed[k].push_back(Eigen::Affine3d::Identity());
    if (auto t = in.find("transform")) placed[k].back() = parse_transform(*t);
    where[k].push_back(in);
    in.finish();
  }
  for (size_t k = 0; k < names.size(); ++k) {
    JsonNode shapes = objects->at(names[k]);
    if (!shapes.is_array()) shapes.fail("expected an array of shapes");
    if (placed[k].size() == 1)
      for (size_t s = 0; s < shapes.size(); ++s)
        parse_shape(shapes[s], lamp_on, seen_triangles, uses, scene, true, &placed[k][0]);
  }
  scene.instances.world_triangles = static_cast<int>(scene.triangles.size());
  for (size_t k = 0; k < names.size(); ++k) {
    if (placed[k].size() < 2) continue;
    JsonNode shapes = objects->at(names[k]);
    ObjectRange range{static_cast<int>(scene.triangles.size()), 0};
    TriangleKeys own;  // duplicates within the object; its instances overlap no one's triangles
    for (size_t s = 0; s < shapes.size(); ++s)
      parse_shape(shapes[s], lamp_on, own, uses, scene, true);
    range.triangle_count = static_cast<int>(scene.triangles.size()) - range.first_triangle;
    if (range.triangle_count == 0) continue;
    const int object = static_cast<int>(scene.instances.objects.size());
    scene.instances.objects.push_back(range);
    scene.object_names.push_back(names[k]);
    for (size_t i = 0; i < placed[k].size(); ++i) {
      Placement p;
      p.object = object;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) p.world_from_object[4 * r + c] = placed[k][i].matrix()(r, c);
      scene.instances.placements.push_back(p);
      check_placed_box(scene, p, where[k][i]);
    }
  }
}

Scene load_scene(const std::string& path, const std::optional<GridRequest>& grid,
                 const std::string& lamp, const std::vector<MaterialOverride>& materials) {
  JsonNode root = read_scene_document(path, materials);
  if (!root.is_object()) root.fail("expected a scene object");
  Scene scene;
  scene.file = path;
  if (root.at("kasha_scene").integer_in(0, 1000) != 1)
    root.at("kasha_scene").fail("unsupported scene version");

  GridRequest request;
  if (auto w = root.find("wavelengths")) request = parse_grid_request(*w);
  if (grid) request = *grid;
  const JsonNode camera = root.at("camera");
  parse_media(root, camera, scene);  // before the camera, which may be in one
  scene.camera = parse_camera(camera);
  const LampChoice lamp_on = choose_lamp(root, lamp, scene);
  parse_textures(root, scene);
  parse_materials(root.at("materials"), scene);
  parse_lights(root, scene);
  if (auto depth = root.find("max_depth")) scene.max_depth = depth->integer_in(0, 1 << 30);

  JsonNode shapes = root.at("shapes");
  TriangleKeys seen_triangles;
  ShapeUses uses;
  uses.materials.assign(scene.material_descs.size(), false);
  for (size_t s = 0; s < shapes.size(); ++s)
    parse_shape(shapes[s], lamp_on, seen_triangles, uses, scene);
  parse_instances(root, lamp_on, seen_triangles, uses, scene);
  if (seen_triangles.dropped > 0)
    warn(seen_triangles.first_dropped + ": " + std::to_string(seen_triangles.dropped) +
         " duplicate triangles (the same vertices as earlier ones) left out, in " +
         std::to_string(seen_triangles.dropped_shapes) + " shape(s) from here on");
  root.finish();
  if (scene.triangles.empty()) root.fail("the scene has no shapes");
  if (lamp_on.spectrum && !uses.lamp)
    root.at("lamps").fail("no shape emits the lamps (give one \"lamp\": true)");

  // A used mix uses its materials (the grid must cover their excitation).
  for (size_t m = uses.materials.size(); m-- > 0;)
    if (uses.materials[m] && scene.material_descs[m].mix)
      mark_mix_used(scene, static_cast<int>(m), uses);
  discretize(request, uses.materials, scene);
  discretize_media(scene);
  check_emitters(scene);
  check_material_textures(scene);
  return scene;
}

}  // namespace kasha
