#include "scene/mesh_file.h"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <assimp/DefaultLogger.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/gzip_input.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "core/warning.h"
#include "scene/ply_mesh.h"

// Debian's Assimp is built with its internal checks on, and a failed one aborts the process from
// inside the library (its handler cannot be set through the installed API). This definition takes
// the place of the library's (every call goes through the dynamic linker) and throws instead: the
// importer fails, and kasha names the file in one line.
namespace Assimp {
void aiAssertViolation(const char* expression, const char* file, int line) {
  throw std::runtime_error(std::string("Assimp's internal check failed (") + expression + " at " +
                           std::filesystem::path(file).filename().string() + ":" +
                           std::to_string(line) + ")");
}
}  // namespace Assimp

namespace kasha {

namespace {

namespace fs = std::filesystem;

// Assimp opens the mesh and a glTF file's buffers through this: each file read once by kasha's
// checked route (a regular file within the size limit), and nothing outside the mesh's own
// folder, so a hostile .gltf cannot make kasha read /etc/passwd as a buffer.
class CheckedFiles : public Assimp::IOSystem {
 public:
  explicit CheckedFiles(const fs::path& mesh) : folder_(fs::weakly_canonical(mesh).parent_path()) {}

  bool Exists(const char* file) const override {
    std::error_code e;
    return inside(file) && fs::is_regular_file(file, e);
  }
  char getOsSeparator() const override { return '/'; }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string(mode).find_first_of("wa+") != std::string::npos) return nullptr;
    if (!inside(file)) {
      refused_ = std::string(file);
      return nullptr;
    }
    const std::string key = fs::weakly_canonical(file).string();
    auto it = contents_.find(key);
    if (it == contents_.end())
      it = contents_.emplace(key, read_input_file(file, kMaxBinaryInputBytes)).first;
    const std::string& bytes = it->second;
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

  // A file Assimp asked for outside the mesh's folder, or empty.
  const std::string& refused() const { return refused_; }

 private:
  bool inside(const char* file) const {
    std::error_code e;
    const fs::path p = fs::weakly_canonical(file, e);
    if (e) return false;
    auto f = folder_.begin(), q = p.begin();
    for (; f != folder_.end(); ++f, ++q)
      if (q == p.end() || *f != *q) return false;
    return true;
  }

  fs::path folder_;
  std::map<std::string, std::string> contents_;
  std::string refused_;
};

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

// What Assimp's message (or its internal check, aiAssertViolation above) says, in kasha's words:
// its own wording ("Validation failed: aiMesh::mFaces[4]::mIndices[0] is out of range") names
// its data structures, not the file's problem.
std::string in_kasha_words(const std::string& library_message) {
  auto has = [&](const char* phrase) { return library_message.find(phrase) != std::string::npos; };
  if (has("mIndices") || has("index") || has("Index"))
    return "a face names a vertex the mesh does not have";
  if (has("no faces")) return "a mesh in the file has no faces";
  if (has("Validation failed")) return "its faces, vertices and buffers do not agree";
  if (has("internal check failed"))
    return "the file is malformed (its reader stopped on an inconsistency)";
  if (has("nable to open") || has("ailed to open")) return "cannot open the file";
  if (has("No suitable reader") || has("magic") || has("Magic"))
    return "the file is not a mesh in the format its name says";
  if (has("end of file") || has("EOF") || has("truncat") || has("too small") ||
      has("Unexpected end"))
    return "the file ends early (truncated?)";
  return "the file is malformed or uses something its reader does not support";
}

}  // namespace

// The import itself, in the reading process.
static ShapeMesh import_mesh(const std::string& path) {
  Assimp::Importer importer;
  auto* files = new CheckedFiles(path);
  importer.SetIOHandler(files);  // the importer owns it
  // Points and lines are not surfaces: dropped, not reported as an error.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType |
                         aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, flags);
  } catch (const Error&) {
    throw;  // a buffer that kasha's checked route refused names itself
  } catch (const std::exception& e) {
    throw Error(printable(path) + ": cannot read mesh: " + in_kasha_words(e.what()));
  }
  if (!files->refused().empty())
    throw Error(printable(path) +
                ": names a file outside its folder: " + printable(files->refused()));
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    throw Error(printable(path) +
                ": cannot read mesh: " + in_kasha_words(importer.GetErrorString()));
  }
  ShapeMesh out;
  bool any_normals = false;
  const TriangleUv fallback = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)};
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const aiVector3D* uv = mesh->HasTextureCoords(0) ? mesh->mTextureCoords[0] : nullptr;
    const aiVector3D* n = mesh->HasNormals() ? mesh->mNormals : nullptr;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      Triangle t;
      TriangleUv tuv = fallback;
      TriangleNormals tn;
      bool has_normals = n != nullptr;
      for (int k = 0; k < 3; ++k) {
        const unsigned i = face.mIndices[k];
        if (i >= mesh->mNumVertices)
          throw Error(printable(path) + ": face " + std::to_string(f + 1) + " names vertex " +
                      std::to_string(i) + " of " + std::to_string(mesh->mNumVertices));
        const aiVector3D& v = mesh->mVertices[i];
        t[k] = Eigen::Vector3d(v.x, v.y, v.z);
        if (uv) tuv[k] = Eigen::Vector2d(uv[i].x, uv[i].y);
        if (n) {
          tn[k] = Eigen::Vector3d(n[i].x, n[i].y, n[i].z);
          const double length = tn[k].norm();
          if (!(length > 0 && std::isfinite(length)))
            has_normals = false;
          else
            tn[k] /= length;
        }
      }
      for (const Eigen::Vector2d& c : tuv)
        if (!std::isfinite(c.x()) || !std::isfinite(c.y())) tuv = fallback;
      if (!has_normals) {
        const Eigen::Vector3d g = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
        tn = {g, g, g};
      }
      any_normals = any_normals || has_normals;
      out.tris.push_back(t);
      out.uv.push_back(tuv);
      out.normals.push_back(tn);
    }
  }
  if (out.tris.empty()) throw Error(printable(path) + ": the mesh has no triangles");
  if (!any_normals) out.normals.clear();
  return out;
}

// The child's answer through the pipe: a status byte, then a message (status 1) or the mesh
// (status 0) as counts and floats — Assimp's own precision, so nothing is lost.
namespace {

void put_bytes(std::string& out, const void* p, size_t n) {
  out.append(static_cast<const char*>(p), n);
}

std::string serialize(const ShapeMesh& m) {
  std::string out(1, '\0');
  const uint64_t n = m.tris.size(), with_normals = m.normals.empty() ? 0 : 1;
  put_bytes(out, &n, sizeof n);
  put_bytes(out, &with_normals, sizeof with_normals);
  out.reserve(out.size() + n * (9 + 6 + 9) * sizeof(float));
  for (size_t i = 0; i < n; ++i) {
    float v[24];
    int k = 0;
    for (const Eigen::Vector3d& p : m.tris[i])
      for (int c = 0; c < 3; ++c) v[k++] = static_cast<float>(p[c]);
    for (const Eigen::Vector2d& t : m.uv[i])
      for (int c = 0; c < 2; ++c) v[k++] = static_cast<float>(t[c]);
    if (with_normals)
      for (const Eigen::Vector3d& q : m.normals[i])
        for (int c = 0; c < 3; ++c) v[k++] = static_cast<float>(q[c]);
    put_bytes(out, v, k * sizeof(float));
  }
  return out;
}

// Throws kasha::Error with the child's message, or returns the mesh.
ShapeMesh deserialize(const std::string& in, const std::string& path) {
  auto fail = [&] {
    throw Error(printable(path) + ": cannot read mesh: the reader's answer is incomplete");
  };
  if (in.empty()) fail();
  if (in[0] != '\0') throw Error(in.substr(1));
  uint64_t n = 0, with_normals = 0;
  if (in.size() < 17) fail();
  std::memcpy(&n, in.data() + 1, 8);
  std::memcpy(&with_normals, in.data() + 9, 8);
  const size_t per = (with_normals ? 24 : 15) * sizeof(float);
  if (n > (in.size() - 17) / per || in.size() != 17 + n * per) fail();
  ShapeMesh m;
  const char* p = in.data() + 17;
  for (uint64_t i = 0; i < n; ++i) {
    float v[24];
    std::memcpy(v, p, per);
    p += per;
    Triangle t;
    TriangleUv uv;
    for (int k = 0; k < 3; ++k) t[k] = Eigen::Vector3d(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    for (int k = 0; k < 3; ++k) uv[k] = Eigen::Vector2d(v[9 + 2 * k], v[10 + 2 * k]);
    m.tris.push_back(t);
    m.uv.push_back(uv);
    if (with_normals) {
      TriangleNormals nn;
      for (int k = 0; k < 3; ++k)
        nn[k] = Eigen::Vector3d(v[15 + 3 * k], v[16 + 3 * k], v[17 + 3 * k]);
      m.normals.push_back(nn);
    }
  }
  return m;
}

}  // namespace

// The reading process: any kasha program started with KASHA_MESH_READER=FILE in its environment
// (by mesh_file_triangles) imports FILE, writes its answer to standard output and exits before
// main. Its importer's messages stay out of the answer.
static bool read_mesh_if_asked() {
  const char* file = std::getenv("KASHA_MESH_READER");
  if (!file) return false;
  std::string answer;
  try {
    answer = serialize(import_mesh(file));
  } catch (const std::exception& e) {
    answer = std::string(1, '\1') + e.what();
  }
  const char* p = answer.data();
  size_t left = answer.size();
  while (left > 0) {
    const ssize_t w = write(STDOUT_FILENO, p, left);
    if (w <= 0) {
      if (w < 0 && errno == EINTR) continue;
      _exit(1);
    }
    p += w;
    left -= static_cast<size_t>(w);
  }
  _exit(0);
}
static const bool kMeshReader = read_mesh_if_asked();

// Assimp reads hostile files in a child process: on files it does not expect, Debian's build can
// read past its buffers and crash (the fuzz harness found one in its PLY reader), which must not
// take kasha with it. The child (this program again, read_mesh_if_asked) imports, sends the
// triangles back through a pipe and exits; a child that dies, hangs or sends something incomplete
// is one line naming the file.
static ShapeMesh read_in_child(const std::string& path);

// A PLY file (or .ply.gz) by kasha's own reader, in this process: it is bounded and fuzzed.
static ShapeMesh read_ply_file(const std::string& path) {
  const PlyMesh mesh = parse_ply(read_input_file_inflated(path, kMaxBinaryInputBytes), path);
  if (mesh.skipped_faces > 0)
    warn(printable(path) + ": " + std::to_string(mesh.skipped_faces) +
         " faces of other than 3 or 4 vertices are left out (as pbrt-v4 leaves them out)");
  return ply_mesh_triangles(mesh, path);
}

ShapeMesh mesh_file_triangles(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply" || (ext == ".gz" && lower_extension(fs::path(path).stem().string()) == ".ply"))
    return read_ply_file(path);
  if (ext != ".gltf" && ext != ".glb" && ext != ".obj")
    throw Error(printable(path) +
                ": not a mesh format kasha reads (.ply, .ply.gz, .gltf, .glb, .obj)");
  check_input_file(path, kMaxBinaryInputBytes);
  // A small self-contained file read before gives the same triangles: kept (a scene loaded again,
  // the fuzz harness's unchanged seeds), so it is not read by a new process each time. A .gltf
  // is not: its buffers are other files.
  static std::mutex cache_lock;
  static std::map<std::string, ShapeMesh> cache;  // by extension and content
  std::string key;
  std::error_code size_error;
  if (ext != ".gltf" && std::filesystem::file_size(path, size_error) <= (1u << 20) && !size_error) {
    key = ext + '\0' + read_input_file(path, 1u << 20);
    std::lock_guard<std::mutex> hold(cache_lock);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  ShapeMesh mesh = read_in_child(path);
  if (!key.empty()) {
    std::lock_guard<std::mutex> hold(cache_lock);
    if (cache.size() >= 16) cache.clear();
    cache.emplace(key, mesh);
  }
  return mesh;
}

// One import in a reader process (mesh_file_triangles).
static ShapeMesh read_in_child(const std::string& path) {
  int fd[2];
  if (pipe2(fd, O_CLOEXEC) != 0)
    throw Error(printable(path) + ": cannot start the mesh reader: " + std::strerror(errno));
  // This same program, started afresh (a fork of a process with OpenCL and TBB threads could
  // inherit a lock one of them held), reads the file and writes its answer to the pipe.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fd[1], STDOUT_FILENO);
  // What a crashing reader prints (a sanitizer's report, Assimp's own) is not kasha's message:
  // the crash is reported in one line below.
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "KASHA_MESH_READER=", 18) != 0) env_strings.push_back(*e);
  env_strings.push_back("KASHA_MESH_READER=" + path);
  std::vector<char*> envp;
  for (std::string& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  char name[] = "kasha-mesh-reader";
  char* argv[] = {name, nullptr};
  pid_t child = -1;
  const int spawned = posix_spawn(&child, "/proc/self/exe", &actions, nullptr, argv, envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    close(fd[0]);
    close(fd[1]);
    throw Error(printable(path) + ": cannot start the mesh reader: " + std::strerror(spawned));
  }
  close(fd[1]);
  std::string answer;
  char buffer[1 << 16];
  // A reader that sends nothing for 2 s plus 1 s per MB of the file is stuck (a hostile file can
  // loop Assimp: a PLY header cut short does) and is stopped. A million-triangle binary PLY
  // (25 MB) reads in about 1.5 s.
  std::error_code size_error;
  const double megabytes =
      static_cast<double>(std::filesystem::file_size(path, size_error)) / (1 << 20);
  const int limit_ms = 2000 + static_cast<int>(1000 * (size_error ? 0.0 : megabytes));
  int quiet_ms = 0;
  bool stuck = false;
  for (;;) {
    pollfd p{fd[0], POLLIN, 0};
    const int ready = poll(&p, 1, 100);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      if ((quiet_ms += 100) >= limit_ms) {
        stuck = true;
        kill(child, SIGKILL);
        break;
      }
      continue;
    }
    const ssize_t r = read(fd[0], buffer, sizeof buffer);
    if (r > 0) {
      answer.append(buffer, static_cast<size_t>(r));
      quiet_ms = 0;
    } else if (r < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  close(fd[0]);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (stuck)
    throw Error(printable(path) + ": cannot read mesh: the reader (Assimp) did not finish in " +
                std::to_string(limit_ms / 1000) + " s");
  if (WIFSIGNALED(status))
    throw Error(printable(path) + ": cannot read mesh: the reader (Assimp) crashed on it (signal " +
                std::to_string(WTERMSIG(status)) + ")");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(printable(path) + ": cannot read mesh: the reader (Assimp) failed");
  return deserialize(answer, path);
}

}  // namespace kasha
