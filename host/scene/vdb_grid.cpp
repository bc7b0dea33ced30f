#include "scene/vdb_grid.h"

#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdint>
#include <mutex>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The named grid of the file (null where it has none), or one line naming the file. With
// `tree` false, only whether it is there.
openvdb::GridBase::Ptr read_grid(const std::string& path, const std::string& shown,
                                 const std::string& name, bool tree) {
  initialize_openvdb();
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

}  // namespace

DensityGrid read_vdb_density(const std::string& path, const std::string& shown,
                             const std::string& grid_name) {
  const openvdb::GridBase::Ptr base = read_grid(path, shown, grid_name, true);
  const std::string who = shown + ": grid \"" + printable(grid_name) + "\"";
  if (!base) throw Error(shown + ": no grid named \"" + printable(grid_name) + "\"");
  const openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  if (!grid) throw Error(who + " holds " + base->valueType() + " values, not float densities");
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

bool vdb_has_grid(const std::string& path, const std::string& grid_name) {
  try {
    return read_grid(path, path, grid_name, false) != nullptr;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace kasha
