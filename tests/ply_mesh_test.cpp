// kasha's PLY reader (host/scene/ply_mesh.cpp) and gzip inputs (host/core/gzip_input.cpp), against
// pbrt-v4's rules (util/mesh.cpp ReadPLY through rply), on small files written byte by byte here:
// - binary data whose first byte is 0x0A (Assimp read such files one byte off), also after CRLF;
// - quads split as pbrt-v4's ConvertToOnlyTriangles, other faces left out, face_indices read;
// - every rply type name for values and list counts, ASCII and both byte orders;
// - texture coordinates under each of pbrt-v4's four pairs of names, and normals;
// - header claims beyond the file's size, truncated files: one line naming the file;
// - gzip: a .ply.gz mesh and a .pbrt.gz scene with a .pbrt.gz Include read as their plain twins.
#include "scene/ply_mesh.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>

#include "core/gzip_input.h"
#include "scene/mesh_file.h"
#include "scene/pbrt/pbrt_import.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

template <typename T>
void put(std::string& s, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

// A float whose first little-endian byte is 0x0A, a newline.
float newline_float() {
  const std::uint32_t bits = 0x3F80000Au;  // 1.0000012
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// A triangle (0, 1, 2) over three vertices, x of the first vertex `x0`.
std::string binary_triangle(const std::string& eol, float x0) {
  std::string s = "ply" + eol + "format binary_little_endian 1.0" + eol + "element vertex 3" + eol +
                  "property float x" + eol + "property float y" + eol + "property float z" + eol +
                  "element face 1" + eol + "property list uchar int vertex_indices" + eol +
                  "end_header" + eol;
  const float v[3][3] = {{x0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (const auto& p : v)
    for (float c : p) put(s, c);
  put<std::uint8_t>(s, 3);
  for (int i : {0, 1, 2}) put<std::int32_t>(s, i);
  return s;
}

TEST(PlyMesh, BinaryDataWhoseFirstByteIsANewlineIsReadFromThatByte) {
  for (const std::string eol : {"\n", "\r\n"}) {
    const PlyMesh m = parse_ply(binary_triangle(eol, newline_float()), "newline.ply");
    ASSERT_EQ(m.p.size(), 3u);
    EXPECT_EQ(m.p[0].x(), static_cast<double>(newline_float()));
    EXPECT_EQ(m.p[2], Eigen::Vector3d(0, 1, 0));
    EXPECT_EQ(m.tris, (std::vector<int>{0, 1, 2}));
  }
  // Through the scene's route too.
  const ShapeMesh t =
      mesh_file_triangles(write_file("newline.ply", binary_triangle("\n", newline_float())));
  ASSERT_EQ(t.tris.size(), 1u);
  EXPECT_EQ(t.tris[0][0].x(), static_cast<double>(newline_float()));
  EXPECT_TRUE(t.normals.empty());
}

TEST(PlyMesh, QuadsSplitAsPbrtV4AndOtherFacesAreLeftOut) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 3\nproperty list uchar int vertex_indices\nproperty int "
      "face_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 0\n4 0 1 2 3 7\n5 0 1 2 3 4 8\n3 2 3 4 9\n";
  const PlyMesh m = parse_ply(ply, "quad.ply");
  EXPECT_EQ(m.quads, (std::vector<int>{0, 1, 3, 2}));  // pbrt-v4's bilinear patch order
  EXPECT_EQ(m.tris, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(m.skipped_faces, 1);
  EXPECT_EQ(m.face_indices, (std::vector<int>{7, 8, 9}));
  const ShapeMesh t = ply_mesh_triangles(m, "quad.ply");
  ASSERT_EQ(t.tris.size(), 3u);
  // ConvertToOnlyTriangles: face corners 0 1 2, then 0 2 3, after the triangles.
  const std::vector<std::array<int, 3>> expected = {{2, 3, 4}, {0, 1, 2}, {0, 2, 3}};
  for (size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(t.tris[i][k], m.p[expected[i][k]]) << i << " " << k;
}

// The triangle of binary_triangle written with `type` for every value and list count.
std::string typed_triangle(const std::string& type, const std::string& format) {
  std::string s = "ply\nformat " + format + " 1.0\nelement vertex 3\nproperty " + type +
                  " x\nproperty " + type + " y\nproperty " + type +
                  " z\nelement face 1\nproperty list " + type + " " + type +
                  " vertex_indices\nend_header\n";
  const int v[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const bool big = format == "binary_big_endian";
  auto value = [&](int x) {
    if (format == "ascii") {
      s += std::to_string(x) + " ";
      return;
    }
    const std::string t = type;
    if (t == "char" || t == "int8")
      put<std::int8_t>(s, x, big);
    else if (t == "uchar" || t == "uint8")
      put<std::uint8_t>(s, x, big);
    else if (t == "short" || t == "int16")
      put<std::int16_t>(s, x, big);
    else if (t == "ushort" || t == "uint16")
      put<std::uint16_t>(s, x, big);
    else if (t == "int" || t == "int32")
      put<std::int32_t>(s, x, big);
    else if (t == "uint" || t == "uint32")
      put<std::uint32_t>(s, x, big);
    else if (t == "float" || t == "float32")
      put<float>(s, x, big);
    else
      put<double>(s, x, big);
  };
  for (const auto& p : v)
    for (int c : p) value(c);
  for (int x : {3, 0, 1, 2}) value(x);
  return s;
}

TEST(PlyMesh, EveryRplyTypeNameReadsInEveryFormat) {
  for (const char* type :
       {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
        "int16", "uint16", "int32", "uint32", "float32", "float64"})
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
      const PlyMesh m = parse_ply(typed_triangle(type, format), "typed.ply");
      ASSERT_EQ(m.p.size(), 3u) << type << " " << format;
      EXPECT_EQ(m.p[1], Eigen::Vector3d(1, 0, 0)) << type << " " << format;
      EXPECT_EQ(m.p[2], Eigen::Vector3d(0, 1, 0)) << type << " " << format;
      EXPECT_EQ(m.tris, (std::vector<int>{0, 1, 2})) << type << " " << format;
    }
  // An ASCII value outside its type's range is refused, as rply refuses it.
  std::string bad = typed_triangle("uchar", "ascii");
  bad.replace(bad.find("end_header\n") + 11, 1, "300");
  EXPECT_NE(error_of([&] { parse_ply(bad, "range.ply"); }).find("range.ply: "), std::string::npos);
}

std::string with_vertex_properties(const std::string& names) {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n";
  std::string values[3];
  std::istringstream in(names);
  std::string name;
  int k = 0;
  while (in >> name) {
    s += "property float " + name + "\n";
    for (int i = 0; i < 3; ++i) values[i] += " " + std::to_string(0.25 * (k + 1) + i);
    ++k;
  }
  s += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const char* p[3] = {"0 0 0", "1 0 0", "0 1 0"};
  for (int i = 0; i < 3; ++i) s += std::string(p[i]) + values[i] + "\n";
  return s + "3 0 1 2\n";
}

TEST(PlyMesh, TextureCoordinatesUnderEachOfPbrtV4sNamesAndNormals) {
  for (const char* names : {"u v", "s t", "texture_u texture_v", "texture_s texture_t"}) {
    const PlyMesh m = parse_ply(with_vertex_properties(names), "uv.ply");
    ASSERT_EQ(m.uv.size(), 3u) << names;
    EXPECT_EQ(m.uv[2], Eigen::Vector2d(2.25, 2.5)) << names;
  }
  // Half a pair is no texture coordinates; pbrt-v4's (0, 0), (1, 0), (1, 1) then.
  const PlyMesh half = parse_ply(with_vertex_properties("texture_s"), "half.ply");
  EXPECT_TRUE(half.uv.empty());
  EXPECT_EQ(ply_mesh_triangles(half, "half.ply").uv[0][2], Eigen::Vector2d(1, 1));
  const PlyMesh n = parse_ply(with_vertex_properties("nx ny nz"), "normals.ply");
  ASSERT_EQ(n.n.size(), 3u);
  EXPECT_EQ(n.n[0], Eigen::Vector3d(0.25, 0.5, 0.75));
  const ShapeMesh t = ply_mesh_triangles(n, "normals.ply");
  ASSERT_EQ(t.normals.size(), 1u);
  EXPECT_NEAR((t.normals[0][0] - Eigen::Vector3d(0.25, 0.5, 0.75).normalized()).norm(), 0, 1e-12);
}

TEST(PlyMesh, ClaimsBeyondTheFileAndTruncatedFilesGetOneLine) {
  const std::string good = binary_triangle("\n", 0.5f);
  std::vector<std::pair<std::string, std::string>> cases;
  for (const char* claim : {"2147483648", "4294967300", "9223372036854775807"}) {
    std::string s = good;
    s.replace(s.find("vertex 3"), 8, std::string("vertex ") + claim);
    cases.push_back({s, std::string("claims ") + claim + " \"vertex\""});
  }
  std::string list = good;
  list[list.size() - 13] = static_cast<char>(255);  // the face's count: 255 indices in 12 bytes
  cases.push_back({list, "a list claims 255"});
  cases.push_back({good.substr(0, good.size() - 5), "truncated?"});
  cases.push_back({good.substr(0, good.size() - 14), "truncated?"});  // inside the vertices
  cases.push_back({good.substr(0, good.find("end_header")), "header ends early"});
  cases.push_back({"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "not a whole number"});
  cases.push_back({"solid x\n", "not a PLY file"});
  std::string index = good;
  index[index.size() - 1] = 9;  // the last index (9 in its top byte): far past 3 vertices
  cases.push_back({index, "names vertex"});
  for (const auto& [bytes, message] : cases) {
    const std::string error =
        error_of([&] { mesh_file_triangles(write_file("claim.ply", bytes)); });
    EXPECT_EQ(error.rfind(write_file("claim.ply", bytes) + ": ", 0), 0u) << error;
    EXPECT_NE(error.find(message), std::string::npos) << message << "\n  gave: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

std::string gzip(const std::string& data) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, 16 + 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, data.size()) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

TEST(GzipInput, CompressedMeshesAndScenesReadAsTheirPlainTwins) {
  const std::string ply = binary_triangle("\n", newline_float());
  const ShapeMesh plain = mesh_file_triangles(write_file("twin.ply", ply));
  const ShapeMesh packed = mesh_file_triangles(write_file("twin.ply.gz", gzip(ply)));
  ASSERT_EQ(packed.tris.size(), 1u);
  EXPECT_EQ(packed.tris[0], plain.tris[0]);
  // Two gzip members one after another are one file, as gzip reads them.
  EXPECT_EQ(gunzip(gzip("ab") + gzip("cd"), "two.gz", 100), "abcd");

  const std::string shape =
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n";
  write_file("part.pbrt.gz", gzip(shape));
  const std::string head = "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const std::string scene = write_file("scene.pbrt.gz", gzip(head + "Include \"part.pbrt.gz\"\n"));
  const std::string twin = write_file("scene.pbrt", head + shape);
  EXPECT_TRUE(is_pbrt_scene(scene));
  EXPECT_EQ(import_pbrt_scene(scene).at("shapes"), import_pbrt_scene(twin).at("shapes"));
}

TEST(GzipInput, BadCompressedDataAndBombsGetOneLine) {
  const std::string packed = gzip(std::string(1 << 20, 'a'));
  struct Case {
    std::string bytes, message;
    std::uint64_t bound;
  };
  const std::vector<Case> cases = {
      {packed.substr(0, packed.size() / 2), "ends early", 1 << 21},
      {"not gzip at all", "not valid gzip data", 1 << 21},
      {packed, "decompresses to more than 65536 bytes", 1 << 16},  // 1 MiB of 'a'
  };
  for (const auto& [bytes, message, bound] : cases) {
    const std::string error = error_of([&] { gunzip(bytes, "x.gz", bound); });
    EXPECT_EQ(error.rfind("x.gz: ", 0), 0u) << error;
    EXPECT_NE(error.find(message), std::string::npos) << message << "\n  gave: " << error;
  }
  const std::string file = write_file("bad.ply.gz", "not gzip at all");
  EXPECT_NE(error_of([&] { mesh_file_triangles(file); }).find("bad.ply.gz: is not valid gzip"),
            std::string::npos);
}

}  // namespace
