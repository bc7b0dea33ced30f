#include "scene/ply_mesh.h"

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

std::string quoted(const std::string& s) {
  return "\"" + printable(s) + "\"";
}

// A value read from the file, as a message shows it (a whole number without decimals).
std::string number_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// rply's types, each under both of its names.
enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

bool find_type(const std::string& word, PlyType& type) {
  static const char* const names[] = {"int8",    "uint8",   "int16", "uint16", "int32", "uint32",
                                      "float32", "float64", "char",  "uchar",  "short", "ushort",
                                      "int",     "uint",    "float", "double"};
  for (int i = 0; i < 16; ++i)
    if (word == names[i]) {
      type = static_cast<PlyType>(i % 8);
      return true;
    }
  return false;
}

size_t type_bytes(PlyType t) {
  static const size_t bytes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return bytes[static_cast<int>(t)];
}

struct Property {
  std::string name;
  bool list = false;
  PlyType type = PlyType::kFloat32;  // a list's values
  PlyType count_type = PlyType::kUint8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int find(const std::string& property) const {
    for (size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == property) return static_cast<int>(i);
    return -1;
  }
};

enum class Storage { kAscii, kLittleEndian, kBigEndian };

struct Header {
  Storage storage = Storage::kAscii;
  std::vector<Element> elements;
  size_t data = 0;  // where the data begins
};

// The bytes of the file and a position in them, read by rply's rules: words are separated by
// " \n\r\t", and reading a word consumes the one character after it, so that the binary data
// begins exactly one character after `end_header` (two after a "\r\n" when the magic line ends so).
class Cursor {
 public:
  Cursor(const std::string& bytes, const std::string& path)
      : b_(bytes), where_(printable(path) + ": cannot read mesh: ") {}

  [[noreturn]] void fail(const std::string& why) const { throw Error(where_ + why); }

  // The next word, or empty at the end of the file.
  std::string word() {
    static const char* const blanks = " \n\r\t";
    while (pos_ < b_.size() && std::strchr(blanks, b_[pos_]) && b_[pos_] != '\0') ++pos_;
    const size_t start = pos_;
    while (pos_ < b_.size() && !(std::strchr(blanks, b_[pos_]) && b_[pos_] != '\0')) ++pos_;
    std::string w = b_.substr(start, pos_ - start);
    if (pos_ < b_.size()) ++pos_;  // the separator
    return w;
  }
  // A word that must be there.
  std::string needed_word(const char* what) {
    std::string w = word();
    if (w.empty()) fail("the PLY header ends early, before its " + std::string(what));
    return w;
  }
  // The rest of the line (rply's comment and obj_info).
  void skip_line() {
    while (pos_ < b_.size() && b_[pos_] != '\n') ++pos_;
    if (pos_ < b_.size()) ++pos_;
  }
  // `n` raw bytes, or a clear refusal when the file ends first.
  const char* take(size_t n, const char* what) {
    if (b_.size() - pos_ < n)
      fail("the file ends early, inside " + std::string(what) + " (truncated?)");
    const char* p = b_.data() + pos_;
    pos_ += n;
    return p;
  }
  size_t pos() const { return pos_; }
  void skip(size_t n) { pos_ += n; }
  size_t left() const { return b_.size() - pos_; }
  const std::string& where() const { return where_; }

 private:
  const std::string& b_;
  std::string where_;
  size_t pos_ = 0;
};

// One `property ...` line.
Property read_property(Cursor& c) {
  Property p;
  std::string type = c.needed_word("property type");
  if (type == "list") {
    p.list = true;
    const std::string count = c.needed_word("list count type"),
                      value = c.needed_word("list value type");
    if (!find_type(count, p.count_type))
      c.fail("the PLY header names an unknown list count type " + quoted(count));
    if (!find_type(value, p.type))
      c.fail("the PLY header names an unknown list value type " + quoted(value));
  } else if (!find_type(type, p.type)) {
    c.fail("the PLY header names an unknown property type " + quoted(type));
  }
  p.name = c.needed_word("property name");
  return p;
}

// An element's count, a non-negative whole number (rply reads it with %ld).
std::uint64_t read_count(Cursor& c, const std::string& element) {
  const std::string w = c.needed_word("element count");
  char* end = nullptr;
  errno = 0;
  const long long n = std::strtoll(w.c_str(), &end, 10);
  if (end == w.c_str() || *end || errno || n < 0)
    c.fail("the PLY element " + quoted(element) + " has count " + quoted(w) +
           ", not a whole number of 0 or more");
  return static_cast<std::uint64_t>(n);
}

Header read_header(Cursor& c, const std::string& bytes) {
  if (bytes.size() < 4 || bytes.compare(0, 3, "ply") != 0 ||
      !std::strchr(" \n\r\t\f\v", bytes[3]) || bytes[3] == '\0')
    c.fail("not a PLY file (it does not begin with \"ply\")");
  const bool crlf = bytes[3] == '\r' && bytes.size() > 4 && bytes[4] == '\n';
  c.skip(3);
  Header h;
  std::string w = c.word();
  if (w != "format") c.fail("the PLY header has no \"format\" line after \"ply\"");
  const std::string storage = c.needed_word("format"), version = c.needed_word("format version");
  if (storage == "ascii")
    h.storage = Storage::kAscii;
  else if (storage == "binary_little_endian")
    h.storage = Storage::kLittleEndian;
  else if (storage == "binary_big_endian")
    h.storage = Storage::kBigEndian;
  else
    c.fail("the PLY format " + quoted(storage) +
           " is none of ascii, binary_little_endian, binary_big_endian");
  if (version != "1.0") c.fail("the PLY version is " + quoted(version) + ", not 1.0");
  for (w = c.needed_word("end_header"); w != "end_header"; w = c.needed_word("end_header")) {
    if (w == "comment" || w == "obj_info") {
      c.skip_line();
    } else if (w == "element") {
      Element e;
      e.name = c.needed_word("element name");
      e.count = read_count(c, e.name);
      h.elements.push_back(e);
    } else if (w == "property") {
      if (h.elements.empty()) c.fail("the PLY header has a property before any element");
      h.elements.back().properties.push_back(read_property(c));
    } else {
      c.fail("the PLY header has an unexpected word " + quoted(w.substr(0, 40)));
    }
  }
  if (crlf && h.storage != Storage::kAscii) c.take(1, "the header's last line end");
  h.data = c.pos();
  return h;
}

// No claim larger than the file can hold gets memory: each instance of an element takes at least
// its scalars' bytes and its lists' counts (binary), or two characters a value (ASCII: a digit and
// a separator).
void check_counts(const Header& h, const Cursor& c) {
  std::uint64_t left = c.left() + 1;  // the last ASCII value needs no separator
  for (const Element& e : h.elements) {
    std::uint64_t least = 0;
    for (const Property& p : e.properties)
      least += h.storage == Storage::kAscii ? 2 : type_bytes(p.list ? p.count_type : p.type);
    if (least == 0) continue;  // nothing to read, nothing allocated
    if (e.count > left / least)
      c.fail("the PLY header claims " + std::to_string(e.count) + " " + quoted(e.name) +
             " elements, more than the file's remaining " + std::to_string(c.left()) +
             " bytes can hold (truncated?)");
    left -= e.count * least;
  }
}

}  // namespace

namespace {

template <typename T>
double binary_value(const char* p, bool swap) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return static_cast<double>(v);
}

// One value of `type`, by rply's rules: binary in the file's byte order; ASCII a word that is
// whole a number in the type's range (integers in base 10).
double read_value(Cursor& c, Storage storage, PlyType type, const char* what) {
  if (storage != Storage::kAscii) {
    const char* p = c.take(type_bytes(type), what);
    const bool swap = storage == Storage::kBigEndian;  // kasha's hosts are little-endian
    switch (type) {
      case PlyType::kInt8:
        return binary_value<std::int8_t>(p, swap);
      case PlyType::kUint8:
        return binary_value<std::uint8_t>(p, swap);
      case PlyType::kInt16:
        return binary_value<std::int16_t>(p, swap);
      case PlyType::kUint16:
        return binary_value<std::uint16_t>(p, swap);
      case PlyType::kInt32:
        return binary_value<std::int32_t>(p, swap);
      case PlyType::kUint32:
        return binary_value<std::uint32_t>(p, swap);
      case PlyType::kFloat32:
        return binary_value<float>(p, swap);
      case PlyType::kFloat64:
        return binary_value<double>(p, swap);
    }
  }
  const std::string w = c.word();
  if (w.empty()) c.fail("the file ends early, inside " + std::string(what) + " (truncated?)");
  char* end = nullptr;
  double v = 0;
  if (type == PlyType::kFloat32 || type == PlyType::kFloat64) {
    v = std::strtod(w.c_str(), &end);
    if (type == PlyType::kFloat32 && (v < -FLT_MAX || v > FLT_MAX)) end = nullptr;
  } else {
    static const double lo[] = {-128, 0, -32768, 0, -2147483648.0, 0};
    static const double hi[] = {127, 255, 32767, 65535, 2147483647.0, 4294967295.0};
    errno = 0;
    v = static_cast<double>(std::strtoll(w.c_str(), &end, 10));
    const int t = static_cast<int>(type);
    if (errno || v < lo[t] || v > hi[t]) end = nullptr;
  }
  if (!end || *end || end == w.c_str())
    c.fail("in " + std::string(what) + ", " + quoted(w.substr(0, 40)) +
           " is not a number of its declared type");
  return v;
}

// What kasha keeps of an element: the property indices that feed the mesh, -1 where absent.
struct VertexLayout {
  int xyz[3] = {-1, -1, -1}, normal[3] = {-1, -1, -1}, uv[2] = {-1, -1};
};

VertexLayout vertex_layout(const Element& e, const Cursor& c) {
  VertexLayout l;
  const char* const xyz[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    l.xyz[k] = e.find(xyz[k]);
    if (l.xyz[k] < 0)
      c.fail("the PLY vertex element has no \"" + std::string(xyz[k]) + "\" property");
  }
  const char* const n[] = {"nx", "ny", "nz"};
  for (int k = 0; k < 3; ++k) l.normal[k] = e.find(n[k]);
  if (l.normal[0] < 0 || l.normal[1] < 0 || l.normal[2] < 0) l.normal[0] = -1;
  // pbrt-v4 takes the first complete pair of these names.
  const char* const uv[][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& pair : uv)
    if (e.find(pair[0]) >= 0 && e.find(pair[1]) >= 0) {
      l.uv[0] = e.find(pair[0]);
      l.uv[1] = e.find(pair[1]);
      break;
    }
  for (int i :
       {l.xyz[0], l.xyz[1], l.xyz[2], l.normal[0], l.normal[1], l.normal[2], l.uv[0], l.uv[1]})
    if (i >= 0 && e.properties[i].list)
      c.fail("the PLY vertex property " + quoted(e.properties[i].name) +
             " is a list, not a number");
  return l;
}

// A list's length: a whole number, at most what the remaining bytes can hold.
std::uint64_t list_length(Cursor& c, Storage storage, const Property& p, const char* what) {
  const double n = read_value(c, storage, p.count_type, what);
  const std::uint64_t least = storage == Storage::kAscii ? 2 : type_bytes(p.type);
  if (!(n >= 0) || n != std::floor(n) || n > static_cast<double>(c.left() / least + 1))
    c.fail("in " + std::string(what) + ", a list claims " + number_text(n) +
           " values, more than the file's remaining " + std::to_string(c.left()) +
           " bytes can hold (truncated?)");
  return static_cast<std::uint64_t>(n);
}

// Reads one instance's properties into `values` (scalars; a list's values go to `list` for the
// property `list_index`, any other list is read and dropped).
void read_instance(Cursor& c, Storage storage, const Element& e, const char* what,
                   std::vector<double>& values, int list_index, std::vector<double>& list) {
  for (size_t i = 0; i < e.properties.size(); ++i) {
    const Property& p = e.properties[i];
    if (!p.list) {
      values[i] = read_value(c, storage, p.type, what);
      continue;
    }
    const std::uint64_t n = list_length(c, storage, p, what);
    const bool keep = static_cast<int>(i) == list_index;
    if (keep) list.clear();
    if (storage != Storage::kAscii && !keep) {
      c.take(n * type_bytes(p.type), what);
      continue;
    }
    for (std::uint64_t k = 0; k < n; ++k) {
      const double v = read_value(c, storage, p.type, what);
      if (keep) list.push_back(v);
    }
  }
}

}  // namespace

namespace {

void read_vertices(Cursor& c, Storage storage, const Element& e, PlyMesh& m) {
  const VertexLayout l = vertex_layout(e, c);
  m.p.resize(e.count);  // check_counts bounded the count by the file's size
  if (l.normal[0] >= 0) m.n.resize(e.count);
  if (l.uv[0] >= 0) m.uv.resize(e.count);
  std::vector<double> v(e.properties.size()), unused;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    read_instance(c, storage, e, "the PLY vertices", v, -1, unused);
    // pbrt-v4 keeps every value as a float.
    auto f = [&](int k) { return static_cast<double>(static_cast<float>(v[k])); };
    m.p[i] = {f(l.xyz[0]), f(l.xyz[1]), f(l.xyz[2])};
    if (l.normal[0] >= 0) m.n[i] = {f(l.normal[0]), f(l.normal[1]), f(l.normal[2])};
    if (l.uv[0] >= 0) m.uv[i] = {f(l.uv[0]), f(l.uv[1])};
  }
}

// A vertex index as pbrt-v4 takes it ((int) of the value).
int vertex_index(const Cursor& c, double v, std::uint64_t face) {
  if (!(v >= 0 && v < 2147483648.0))
    c.fail("PLY face " + std::to_string(face + 1) + " names vertex " + number_text(v) +
           ", not a vertex index");
  return static_cast<int>(v);
}

void read_faces(Cursor& c, Storage storage, const Element& e, PlyMesh& m) {
  const int indices = e.find("vertex_indices"), face_index = e.find("face_indices");
  if (indices < 0) c.fail("the PLY face element has no \"vertex_indices\" property");
  if (!e.properties[indices].list) c.fail("the PLY face property \"vertex_indices\" is not a list");
  if (face_index >= 0 && e.properties[face_index].list)
    c.fail("the PLY face property \"face_indices\" is a list, not a number");
  std::vector<double> v(e.properties.size()), list;
  for (std::uint64_t f = 0; f < e.count; ++f) {
    read_instance(c, storage, e, "the PLY faces", v, indices, list);
    if (face_index >= 0)
      m.face_indices.push_back(
          std::isnan(v[face_index])
              ? 0
              : static_cast<int>(std::clamp(v[face_index], -2147483648.0, 2147483647.0)));
    if (list.size() == 3) {
      for (double i : list) m.tris.push_back(vertex_index(c, i, f));
    } else if (list.size() == 4) {
      // pbrt-v4 keeps a quad as a bilinear patch: corners 0, 1, 3, 2 of the face.
      for (int k : {0, 1, 3, 2}) m.quads.push_back(vertex_index(c, list[k], f));
    } else {
      ++m.skipped_faces;
    }
  }
}

void skip_element(Cursor& c, Storage storage, const Element& e) {
  if (e.properties.empty()) return;
  std::vector<double> v(e.properties.size()), unused;
  for (std::uint64_t i = 0; i < e.count; ++i)
    read_instance(c, storage, e, "the PLY data", v, -1, unused);
}

}  // namespace

PlyMesh parse_ply(const std::string& bytes, const std::string& path) {
  Cursor c(bytes, path);
  const Header h = read_header(c, bytes);
  check_counts(h, c);
  PlyMesh m;
  bool vertices = false, faces = false;
  // pbrt-v4 (rply) reads the first element of each name; later ones are data it skips.
  for (const Element& e : h.elements) {
    if (e.name == "vertex" && !vertices) {
      read_vertices(c, h.storage, e, m);
      vertices = true;
    } else if (e.name == "face" && !faces) {
      read_faces(c, h.storage, e, m);
      faces = true;
    } else {
      skip_element(c, h.storage, e);
    }
  }
  if (!vertices || !faces || m.p.empty() ||
      (m.tris.empty() && m.quads.empty() && m.skipped_faces == 0))
    c.fail("the PLY file has no vertices or no faces");
  for (const std::vector<int>* list : {&m.tris, &m.quads})
    for (int i : *list)
      if (static_cast<size_t>(i) >= m.p.size())
        c.fail("a PLY face names vertex " + std::to_string(i) + ", but the file has " +
               std::to_string(m.p.size()) + " vertices (0 to " + std::to_string(m.p.size() - 1) +
               ")");
  return m;
}

ShapeMesh ply_mesh_triangles(const PlyMesh& m, const std::string& path) {
  // pbrt-v4's ConvertToOnlyTriangles: a quad (0, 1, 3, 2 of the face) gives faces 0 1 2 and 0 2 3.
  std::vector<int> tris = m.tris;
  tris.reserve(tris.size() + m.quads.size() / 4 * 6);
  for (size_t q = 0; q + 3 < m.quads.size(); q += 4)
    for (int k : {0, 1, 3, 0, 3, 2}) tris.push_back(m.quads[q + k]);
  if (tris.empty()) throw Error(printable(path) + ": the mesh has no triangles");
  ShapeMesh out;
  bool any_normals = false;
  const TriangleUv fallback = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)};
  for (size_t t = 0; t < tris.size(); t += 3) {
    Triangle tri;
    TriangleUv tuv = fallback;
    TriangleNormals tn;
    bool has_normals = !m.n.empty();
    for (int k = 0; k < 3; ++k) {
      const size_t i = static_cast<size_t>(tris[t + k]);
      tri[k] = m.p[i];
      if (!m.uv.empty()) tuv[k] = m.uv[i];
      if (!m.n.empty()) {
        const double length = m.n[i].norm();
        has_normals = has_normals && length > 0 && std::isfinite(length);
        tn[k] = m.n[i] / length;
      }
    }
    for (const Eigen::Vector2d& c : tuv)
      if (!std::isfinite(c.x()) || !std::isfinite(c.y())) tuv = fallback;
    if (!has_normals) {
      const Eigen::Vector3d g = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
      tn = {g, g, g};
    }
    any_normals = any_normals || has_normals;
    out.tris.push_back(tri);
    out.uv.push_back(tuv);
    out.normals.push_back(tn);
  }
  if (!any_normals) out.normals.clear();
  return out;
}

}  // namespace kasha
