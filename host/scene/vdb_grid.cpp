#include "scene/vdb_grid.h"

// clang-format off: before NanoVDB 32.4's GridValidator.h, which uses std::cerr unincluded.
#include <iostream>
// clang-format on
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/NanoToOpenVDB.h>
#include <openvdb/openvdb.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// Whether the file starts as a NanoVDB file does (pbrt-v4's own grids, .nvdb) rather than as
// an OpenVDB one: the contents decide, as each library's reader would.
bool is_nanovdb_file(const std::string& path, const std::string& shown) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) throw Error(shown + ": cannot open it");
  uint64_t magic = 0;
  return in.read(reinterpret_cast<char*>(&magic), sizeof magic) &&
         (magic == NANOVDB_MAGIC_NUMBER ||
          magic == nanovdb::io::reverseEndianness(NANOVDB_MAGIC_NUMBER));
}

// NanoVDB's reader trusts the counts and sizes in a file's segment headers (allocating what they
// say): they are checked against the file's length first, so a damaged file is one line.
void check_nanovdb_headers(const std::string& path, const std::string& shown) {
  std::ifstream in(path, std::ios::binary);
  const uint64_t length = std::filesystem::file_size(path);
  uint64_t at = 0;
  nanovdb::io::Header header;
  while (at < length && in.read(reinterpret_cast<char*>(&header), sizeof header)) {
    at += sizeof header;
    if (header.magic != NANOVDB_MAGIC_NUMBER) return;  // NanoVDB's reader says what is wrong
    // The segment's grid headers, then their grids' bytes.
    uint64_t data = 0;
    for (int g = 0; g < header.gridCount; ++g) {
      nanovdb::io::MetaData meta;
      if (!in.read(reinterpret_cast<char*>(&meta), sizeof meta) || meta.nameSize > length - at)
        throw Error(shown + ": a damaged NanoVDB file (a grid's header runs past its end)");
      at += sizeof meta + meta.nameSize;
      in.seekg(meta.nameSize, std::ios::cur);
      // Uncompressed, a grid's bytes in memory are its bytes on disk; a zipped one is capped.
      const bool plain = header.codec == nanovdb::io::Codec::NONE;
      if (meta.fileSize > length || (plain && meta.gridSize != meta.fileSize) ||
          meta.gridSize > (uint64_t(1) << 36))
        throw Error(shown + ": a damaged NanoVDB file (a grid's size disagrees with the file's)");
      data += meta.fileSize;
    }
    if (at > length || data > length - at)
      throw Error(shown + ": a damaged NanoVDB file (its grids run past its end)");
    at += data;
    in.seekg(static_cast<std::streamoff>(at));
  }
}

// What NanoVDB's validator reads before it can check anything (the grid's and tree's headers,
// the root's table, each level's run of nodes) lies inside the buffer read: a damaged size field
// would otherwise send it, or the checksum's walk, past the buffer's end.
void check_nanovdb_layout(const nanovdb::GridHandle<nanovdb::HostBuffer>& handle,
                          const std::string& who) {
  using Tree = nanovdb::NanoTree<float>;
  const uint64_t size = handle.size(), head = sizeof(nanovdb::GridData) + sizeof(Tree::DataType);
  const uint8_t* data = handle.data();
  const auto damaged = [&](const char* what) {
    return Error(who + ": a damaged NanoVDB file (" + what + ")");
  };
  if (!data || size < head) throw damaged("its grid is shorter than its headers");
  const auto* grid = reinterpret_cast<const nanovdb::GridData*>(data);
  if (grid->mMagic != NANOVDB_MAGIC_NUMBER || grid->mGridSize != size)
    throw damaged("its grid's header disagrees with its size");
  const auto* tree = reinterpret_cast<const Tree::DataType*>(data + sizeof(nanovdb::GridData));
  const uint64_t tree_at = sizeof(nanovdb::GridData);
  const uint64_t node_size[3] = {sizeof(nanovdb::NanoLeaf<float>),
                                 sizeof(nanovdb::NanoLower<float>),
                                 sizeof(nanovdb::NanoUpper<float>)};
  for (int level = 0; level < 3; ++level) {
    const uint64_t at = tree->mNodeOffset[level], count = tree->mNodeCount[level];
    if (count > 0 && (at > size - tree_at || count > (size - tree_at - at) / node_size[level]))
      throw damaged("its nodes run past its end");
  }
  const uint64_t root = tree->mNodeOffset[3];
  const uint64_t root_head = sizeof(nanovdb::NanoRoot<float>);
  if (root > size - tree_at || root_head > size - tree_at - root)
    throw damaged("its root runs past its end");
  const auto* root_data =
      reinterpret_cast<const nanovdb::NanoRoot<float>::DataType*>(data + tree_at + root);
  if (root_data->mTableSize >
      (size - tree_at - root - root_head) / sizeof(nanovdb::NanoRoot<float>::Tile))
    throw damaged("its root's table runs past its end");
}

// The named float grid of a NanoVDB file as an OpenVDB grid (null where it has none), checked by
// NanoVDB's validator (its checksum where the file has one) before it is walked.
openvdb::GridBase::Ptr read_nanovdb_grid(const std::string& path, const std::string& shown,
                                         const std::string& name, bool tree) {
  const std::string who = shown + ": grid \"" + printable(name) + "\"";
  nanovdb::GridHandle<nanovdb::HostBuffer> handle;
  try {
    check_nanovdb_headers(path, shown);
    if (!nanovdb::io::hasGrid(path, name)) return nullptr;
    if (!tree) return openvdb::FloatGrid::create();  // only whether it is there
    handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // NanoVDB's messages run over lines and tabs: one line of single spaces here.
    std::string why;
    for (const char c : std::string(e.what()))
      if (!std::isspace(static_cast<unsigned char>(c))) why += c;
      else if (!why.empty() && why.back() != ' ') why += ' ';
    throw Error(shown + ": cannot read it as a NanoVDB file (" + printable(why) + ")");
  }
  const nanovdb::GridMetaData* meta = handle.gridMetaData();
  if (!meta || handle.size() < sizeof(nanovdb::GridData))
    throw Error(who + ": a damaged NanoVDB file (no grid in its buffer)");
  const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
  if (!grid) {
    const nanovdb::GridType type = meta->gridType();  // toStr's table stops at End
    throw Error(who + " holds " +
                (type < nanovdb::GridType::End ? nanovdb::toStr(type) : "unknown") +
                " values, not floats");
  }
  check_nanovdb_layout(handle, who);
  if (!nanovdb::isValid(*grid, true, false))
    throw Error(who + ": a damaged NanoVDB file (NanoVDB's validator refuses it)");
  openvdb::FloatGrid::Ptr open = nanovdb::nanoToOpenVDB(*grid);
  // The map as NanoVDB applies it (pbrt-v4 samples through it): NanoVDB 32.4's converter hands
  // OpenVDB its rotation transposed. Its columns: where the index axes go.
  const nanovdb::Vec3d o = grid->indexToWorld(nanovdb::Vec3d(0, 0, 0));
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  for (int a = 0; a < 3; ++a) {
    nanovdb::Vec3d e(0, 0, 0);
    e[a] = 1;
    const nanovdb::Vec3d axis = grid->indexToWorld(e) - o;
    for (int r = 0; r < 3; ++r) m(a, r) = axis[r];  // OpenVDB's rows map index axis a
    m(3, a) = o[a];
  }
  open->setTransform(openvdb::math::Transform::createLinearTransform(m));
  return open;
}

// The named grid of the file (null where it has none), or one line naming the file. With
// `tree` false, only whether it is there. A NanoVDB file is read through NanoVDB and converted.
openvdb::GridBase::Ptr read_grid(const std::string& path, const std::string& shown,
                                 const std::string& name, bool tree) {
  initialize_openvdb();
  if (is_nanovdb_file(path, shown)) return read_nanovdb_grid(path, shown, name, tree);
  try {
    openvdb::io::File file(path);
    file.open(false);  // no delayed loading: the file is read once and closed
    openvdb::GridBase::Ptr grid;
    if (file.hasGrid(name)) grid = tree ? file.readGrid(name) : file.readGridMetadata(name);
    file.close();
    return grid;
  } catch (const std::exception& e) {
    throw Error(shown + ": cannot read it as an OpenVDB file (" + printable(e.what()) + ")");
  }
}

// OpenVDB's maps take row vectors (world = index · M); Eigen's affine takes columns.
Eigen::Affine3d index_to_world(const openvdb::GridBase& grid, const std::string& who) {
  const openvdb::math::Transform& t = grid.transform();
  if (!t.isLinear()) throw Error(who + ": its transform is not affine (a frustum map?)");
  const openvdb::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.linear()(r, c) = m(c, r);
    a.translation()(r) = m(3, r);
  }
  if (!a.matrix().allFinite() || std::abs(a.linear().determinant()) < 1e-30)
    throw Error(who + ": its transform is singular or not finite");
  return a;
}

// The file's float grid of that name, or one line.
openvdb::FloatGrid::Ptr read_float_grid(const std::string& path, const std::string& shown,
                                        const std::string& grid_name, const std::string& who) {
  const openvdb::GridBase::Ptr base = read_grid(path, shown, grid_name, true);
  if (!base) throw Error(shown + ": no grid named \"" + printable(grid_name) + "\"");
  const openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (!grid) throw Error(who + " holds " + base->valueType() + " values, not floats");
  return grid;
}

}  // namespace

DensityGrid read_vdb_density(const std::string& path, const std::string& shown,
                             const std::string& grid_name) {
  const std::string who = shown + ": grid \"" + printable(grid_name) + "\"";
  const openvdb::FloatGrid::Ptr grid = read_float_grid(path, shown, grid_name, who);
  if (grid->getGridClass() == openvdb::GRID_LEVEL_SET)
    throw Error(who + " is a level set, not a fog volume of densities");
  // Beyond the active voxels a grid holds its background: a medium without end unless it is 0.
  if (grid->background() != 0.0f) throw Error(who + ": its background must be 0");
  DensityGrid d;
  d.to_world = index_to_world(*grid, who);
  const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
  if (active.empty()) throw Error(who + " has no active voxels");
  // One background voxel on each side, so trilinear reconstruction falls to 0 as OpenVDB's does.
  // In 64 bits: a file's coordinates may sit at the ends of int's range.
  const int64_t lo[3] = {int64_t(active.min().x()) - 1, int64_t(active.min().y()) - 1,
                         int64_t(active.min().z()) - 1};
  int64_t n[3];
  for (int a = 0; a < 3; ++a) {
    n[a] = int64_t(active.max()[a]) + 1 - lo[a] + 1;
    if (lo[a] < INT32_MIN || lo[a] + n[a] - 1 > INT32_MAX)
      throw Error(who + ": its voxels reach the ends of OpenVDB's coordinate range");
  }
  if (double(n[0]) * double(n[1]) * double(n[2]) > static_cast<double>(1 << 28))
    throw Error(who + ": " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                std::to_string(n[2]) +
                " voxels with its border; a grid holds at most 2^28 samples");
  d.nx = static_cast<int>(n[0]), d.ny = static_cast<int>(n[1]), d.nz = static_cast<int>(n[2]);
  d.values.reserve(static_cast<size_t>(d.nx) * d.ny * d.nz);
  const openvdb::FloatGrid::ConstAccessor at = grid->getConstAccessor();
  for (int z = 0; z < d.nz; ++z)
    for (int y = 0; y < d.ny; ++y)
      for (int x = 0; x < d.nx; ++x) {
        const openvdb::Coord c(int(lo[0] + x), int(lo[1] + y), int(lo[2] + z));
        const float v = at.getValue(c);
        // The JSON grids' bound: σ times a density must stay finite in the kernels.
        if (!(v >= 0 && v <= 1e30f))
          throw Error(who + ": a density must be finite, not negative and at most 1e30 (voxel " +
                      std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " +
                      std::to_string(c.z()) + ")");
        d.values.push_back(v);
      }
  // Sample k sits at the centre of cell k of [p0, p1]: index lo + k.
  d.p0 =
      Eigen::Vector3d(double(lo[0]), double(lo[1]), double(lo[2])) - Eigen::Vector3d::Constant(0.5);
  d.p1 = d.p0 + Eigen::Vector3d(double(n[0]), double(n[1]), double(n[2]));
  return d;
}

std::vector<float> read_vdb_on_lattice(const std::string& path, const std::string& shown,
                                       const std::string& grid_name, const DensityGrid& lattice) {
  const std::string who = shown + ": grid \"" + printable(grid_name) + "\"";
  const openvdb::FloatGrid::Ptr grid = read_float_grid(path, shown, grid_name, who);
  if (!index_to_world(*grid, who).isApprox(lattice.file_map, 1e-9))
    throw Error(who + ": its voxels do not line up with the density's (another transform)");
  // The lattice's samples are at whole indices from p0 + ½ (read_vdb_density).
  const Eigen::Vector3d lo = lattice.p0 + Eigen::Vector3d::Constant(0.5);
  std::vector<float> values;
  values.reserve(static_cast<size_t>(lattice.nx) * lattice.ny * lattice.nz);
  const openvdb::FloatGrid::ConstAccessor at = grid->getConstAccessor();
  for (int z = 0; z < lattice.nz; ++z)
    for (int y = 0; y < lattice.ny; ++y)
      for (int x = 0; x < lattice.nx; ++x) {
        const openvdb::Coord c(static_cast<int>(std::lround(lo.x())) + x,
                               static_cast<int>(std::lround(lo.y())) + y,
                               static_cast<int>(std::lround(lo.z())) + z);
        const float v = at.getValue(c);
        if (!(std::abs(v) <= 1e30f))
          throw Error(who + ": a value must be finite (voxel " + std::to_string(c.x()) + ", " +
                      std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")");
        values.push_back(v);
      }
  return values;
}

bool vdb_has_grid(const std::string& path, const std::string& grid_name) {
  try {
    return read_grid(path, path, grid_name, false) != nullptr;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace kasha
