#include "mesh_writers.h"

#include <cstdint>
#include <cstring>
#include <sstream>

namespace kasha::test {

namespace {

template <class T> void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace

TestMesh tent_mesh() {
  TestMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0.5f, 1}, {0, 0.25f, 1}};
  m.normals = {{0, 1, 0}, {0, 0.6f, 0.8f}, {0, 0.8f, -0.6f}, {0.6f, 0.8f, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0.75f}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

std::string mesh_obj(const TestMesh& m) {
  std::ostringstream s;
  for (auto& p : m.positions) s << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (auto& t : m.uvs) s << "vt " << t[0] << " " << t[1] << "\n";
  for (auto& n : m.normals) s << "vn " << n[0] << " " << n[1] << " " << n[2] << "\n";
  for (auto& f : m.faces) {
    s << "f";
    for (int v : f) s << " " << v + 1 << "/" << v + 1 << "/" << v + 1;
    s << "\n";
  }
  return s.str();
}

std::string mesh_ply(const TestMesh& m, bool binary) {
  std::ostringstream h;
  h << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex "
    << m.positions.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
       "property float nz\nproperty float s\nproperty float t\nelement face "
    << m.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string s = h.str();
  if (binary) {
    for (size_t i = 0; i < m.positions.size(); ++i) {
      for (float v : m.positions[i]) put(s, v);
      for (float v : m.normals[i]) put(s, v);
      for (float v : m.uvs[i]) put(s, v);
    }
    for (auto& f : m.faces) {
      put(s, static_cast<unsigned char>(3));
      for (int v : f) put(s, static_cast<int32_t>(v));
    }
    return s;
  }
  std::ostringstream t;
  for (size_t i = 0; i < m.positions.size(); ++i)
    t << m.positions[i][0] << " " << m.positions[i][1] << " " << m.positions[i][2] << " " << m.normals[i][0] << " "
      << m.normals[i][1] << " " << m.normals[i][2] << " " << m.uvs[i][0] << " " << m.uvs[i][1] << "\n";
  for (auto& f : m.faces) t << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  return s + t.str();
}

std::string mesh_gltf_buffer(const TestMesh& m) {
  std::string b;
  for (auto& p : m.positions)
    for (float v : p) put(b, v);
  for (auto& n : m.normals)
    for (float v : n) put(b, v);
  for (auto& t : m.uvs) {
    put(b, t[0]);
    put(b, 1.0f - t[1]);
  }
  for (auto& f : m.faces)
    for (int v : f) put(b, static_cast<uint16_t>(v));
  while (b.size() % 4) b.push_back('\0');
  return b;
}

std::string mesh_gltf(const TestMesh& m, const std::string& uri, const std::string& node_extra) {
  const size_t n = m.positions.size(), vec3 = 12 * n, vec2 = 8 * n, idx = 6 * m.faces.size();
  std::ostringstream s;
  s << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0)"
    << node_extra << R"(}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
  "buffers": [{"byteLength": )"
    << mesh_gltf_buffer(m).size() << (uri.empty() ? "" : R"(, "uri": ")" + uri + "\"") << R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )"
    << vec3 << R"(}, {"buffer": 0, "byteOffset": )" << vec3 << R"(, "byteLength": )" << vec3
    << R"(}, {"buffer": 0, "byteOffset": )" << 2 * vec3 << R"(, "byteLength": )" << vec2
    << R"(}, {"buffer": 0, "byteOffset": )" << 2 * vec3 + vec2 << R"(, "byteLength": )" << idx << R"(}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": )"
    << n << R"(, "type": "VEC3", "min": [-1e9, -1e9, -1e9], "max": [1e9, 1e9, 1e9]},
    {"bufferView": 1, "componentType": 5126, "count": )"
    << n << R"(, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": )"
    << n << R"(, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": )"
    << 3 * m.faces.size() << R"(, "type": "SCALAR"}]})";
  return s.str();
}

std::string mesh_glb(const TestMesh& m) {
  std::string json = mesh_gltf(m, "");
  while (json.size() % 4) json.push_back(' ');
  const std::string bin = mesh_gltf_buffer(m);
  std::string out;
  put(out, uint32_t(0x46546C67));  // "glTF"
  put(out, uint32_t(2));
  put(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  put(out, uint32_t(json.size()));
  put(out, uint32_t(0x4E4F534A));  // "JSON"
  out += json;
  put(out, uint32_t(bin.size()));
  put(out, uint32_t(0x004E4942));  // "BIN"
  out += bin;
  return out;
}

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  auto byte = [&](size_t k) { return static_cast<unsigned>(static_cast<unsigned char>(in[k])); };
  for (; i + 2 < in.size(); i += 3) {
    unsigned v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
  }
  if (i + 1 == in.size()) {
    unsigned v = byte(i) << 16;
    out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    unsigned v = byte(i) << 16 | byte(i + 1) << 8;
    out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
  }
  return out;
}

}  // namespace kasha::test
