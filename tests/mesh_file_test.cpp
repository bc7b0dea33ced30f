// Mesh files ("type": "mesh", host/scene/mesh_file.cpp, docs/formats.md#mesh-files): PLY by
// kasha's own reader, glTF and OBJ through Assimp:
// - One mesh written by hand as OBJ (read by kasha's own "obj" path), ASCII PLY, binary PLY,
//   glTF with an embedded buffer, glTF with an external .bin and GLB gives the same triangles,
//   texture coordinates and shading normals, value for value, and the same image bit for bit.
// - A glTF node's transform is applied as the scene's "transform" would be.
// - Bad mesh files get one line naming the file: an unknown format, a truncated binary PLY, a
//   face naming a missing vertex, a NaN vertex, a buffer outside the mesh's folder, an empty file.
#include <gtest/gtest.h>


#include "mesh_writers.h"
#include "render_support.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

const TestMesh kTent = tent_mesh();

std::string scene_with(const std::string& name, const std::string& type, const std::string& mesh,
                       const std::string& extra = "") {
  return write_file(name, R"({"kasha_scene": 1,
  "camera": {"position": [0.5, 2, 2.5], "look_at": [0.5, 0.2, 0.5], "fov_deg": 40, "width": 12, "height": 12},
  "materials": {"grey": {"passive": {"reflectance": 0.5}}},
  "shapes": [{"type": ")" + type + R"(", "file": ")" + mesh + R"(", "material": "grey")" + extra + R"(},
             {"type": "quad", "corner": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1], "material": "grey",
              "emission": 1}]})");
}

void expect_same_geometry(const Scene& a, const Scene& b, const std::string& label) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size()) << label;
  ASSERT_EQ(a.normals.size(), b.normals.size()) << label;
  for (size_t i = 0; i < a.triangles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a.triangles[i].v0[c], b.triangles[i].v0[c]) << label << " triangle " << i;
      EXPECT_EQ(a.triangles[i].v1[c], b.triangles[i].v1[c]) << label << " triangle " << i;
      EXPECT_EQ(a.triangles[i].v2[c], b.triangles[i].v2[c]) << label << " triangle " << i;
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.uvs[i][k].x(), b.uvs[i][k].x(), 1e-7) << label << " uv " << i;
      EXPECT_NEAR(a.uvs[i][k].y(), b.uvs[i][k].y(), 1e-7) << label << " uv " << i;
      if (!a.normals.empty()) {
        EXPECT_LT((a.normals[i][k] - b.normals[i][k]).norm(), 1e-7) << label << " normal " << i;
      }
    }
  }
}

TEST(MeshFile, PlyGltfAndGlbTwinsOfAnObjGiveTheSameTrianglesAndImage) {
  const std::string obj = write_file("tent.obj", mesh_obj(kTent));
  const std::string ply_a = write_file("tent_ascii.ply", mesh_ply(kTent, false));
  const std::string ply_b = write_file("tent_binary.ply", mesh_ply(kTent, true));
  const std::string gltf_embedded =
      write_file("tent_embedded.gltf", mesh_gltf(kTent, "data:application/octet-stream;base64," + base64(mesh_gltf_buffer(kTent))));
  write_file("tent.bin", mesh_gltf_buffer(kTent));
  const std::string gltf_external = write_file("tent_external.gltf", mesh_gltf(kTent, "tent.bin"));
  const std::string glb_file = write_file("tent.glb", mesh_glb(kTent));

  const std::string reference = scene_with("tent_obj.json", "obj", obj);
  const Scene ref = load_scene(reference);
  ASSERT_EQ(ref.triangles.size(), 4u);  // the tent's two and the lamp's two
  ASSERT_TRUE(ref.shading_normals());
  const std::vector<std::pair<std::string, std::string>> twins = {
      {"OBJ through Assimp", obj},         {"ASCII PLY", ply_a}, {"binary PLY", ply_b},
      {"glTF, embedded", gltf_embedded}, {"glTF, external .bin", gltf_external}, {"GLB", glb_file}};
  int k = 0;
  for (const auto& [label, file] : twins) {
    const Scene twin = load_scene(scene_with("tent_" + std::to_string(k++) + ".json", "mesh", file));
    expect_same_geometry(ref, twin, label);
  }
  // Same triangles, same BVH, same image.
  RenderSettings s;
  s.passes = 1;
  s.integrator_settings.spp = 4;
  const RenderResult a = render_scene(reference, s);
  const RenderResult b = render_scene(scene_with("tent_ply.json", "mesh", ply_b), s);
  EXPECT_EQ(a.image.xyz, b.image.xyz);
  EXPECT_EQ(a.image.spectral, b.image.spectral);
}

TEST(MeshFile, AGltfNodeTransformIsApplied) {
  const std::string obj = write_file("moved.obj", mesh_obj(kTent));
  const Scene ref = load_scene(scene_with(
      "moved_obj.json", "obj", obj, R"(, "transform": {"scale": 2, "translate": [1, 0.5, -1]})"));
  const std::string gltf =
      write_file("moved.gltf", mesh_gltf(kTent, "data:application/octet-stream;base64," + base64(mesh_gltf_buffer(kTent)),
                                         R"(, "scale": [2, 2, 2], "translation": [1, 0.5, -1])"));
  expect_same_geometry(ref, load_scene(scene_with("moved_gltf.json", "mesh", gltf)), "glTF node transform");
}

TEST(MeshFile, BadMeshFilesGetOneLineNamingTheFile) {
  std::string truncated = mesh_ply(kTent, true);
  truncated.resize(truncated.size() - 20);
  std::string bad_index = mesh_ply(kTent, false);
  bad_index.replace(bad_index.rfind("3 0 2 3"), 7, "3 0 2 9");
  std::string nan_vertex = mesh_ply(kTent, false);
  nan_vertex.replace(nan_vertex.find("\n1 0 0 "), 7, "\n1 nan 0 ");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {write_file("bad.stl", "solid x\nendsolid x\n"), "not a mesh format kasha reads"},
      {write_file("truncated.ply", truncated), "truncated.ply: cannot read mesh"},
      {write_file("bad_index.ply", bad_index), "bad_index.ply"},
      {write_file("nan_vertex.ply", nan_vertex), "not finite"},
      {write_file("outside.gltf", mesh_gltf(kTent, "../outside.bin")), "outside.gltf: names a file outside its folder"},
      {write_file("empty.ply", ""), "empty.ply"},
      // Assimp's own wording ("OBJ: vertex index out of range", "No suitable reader found") is
      // put in kasha's.
      {write_file("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
       "bad_index.obj: cannot read mesh: a face names a vertex the mesh does not have"},
      {write_file("garbage.glb", "garbage"), "garbage.glb: cannot read mesh: the file is not a mesh in the format"},
      // Assimp looped on this header cut short (kasha's PLY reader refuses it at once).
      {write_file("looping.ply", "ply\nformat binary_little_endian 1.0\neleme"), "looping.ply: cannot read mesh"},
  };
  int k = 0;
  for (const auto& [file, message] : cases) {
    const std::string scene = scene_with("bad_mesh_" + std::to_string(k++) + ".json", "mesh", file);
    const std::string error = error_of([&] { load_scene(scene); });
    EXPECT_NE(error.find(message), std::string::npos) << file << "\n  gave: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    for (const char* library : {"Assimp", "aiMesh", "Validation failed", "OBJ:", "No suitable reader"})
      EXPECT_EQ(error.find(library), std::string::npos) << "library wording: " << error;
  }
}

}  // namespace
