#include "vdb_writer.h"

#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

namespace kasha::test {

namespace {

// Eigen's column-vector affine as OpenVDB's row-vector map (world = index · M).
openvdb::math::Transform::Ptr transform_of(const Eigen::Affine3d& a) {
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(c, r) = a.linear()(r, c);
    m(3, r) = a.translation()(r);
  }
  return openvdb::math::Transform::createLinearTransform(m);
}

// The grid as an OpenVDB float grid.
openvdb::FloatGrid::Ptr openvdb_grid(const TestVdbGrid& g) {
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(g.background);
  grid->setName(g.name);
  grid->setTransform(transform_of(g.index_to_world));
  grid->setGridClass(g.level_set ? openvdb::GRID_LEVEL_SET : openvdb::GRID_FOG_VOLUME);
  openvdb::FloatGrid::Accessor at = grid->getAccessor();
  for (int z = 0; z < g.size[2]; ++z)
    for (int y = 0; y < g.size[1]; ++y)
      for (int x = 0; x < g.size[0]; ++x) {
        const float v = g.values[(static_cast<size_t>(z) * g.size[1] + y) * g.size[0] + x];
        if (v != 0)
          at.setValue(openvdb::Coord(g.origin[0] + x, g.origin[1] + y, g.origin[2] + z), v);
      }
  return grid;
}

}  // namespace

void write_vdb(const std::string& path, const std::vector<TestVdbGrid>& grids) {
  openvdb::initialize();
  openvdb::GridPtrVec out;
  for (const TestVdbGrid& g : grids) out.push_back(openvdb_grid(g));
  openvdb::io::File(path).write(out);
}

void write_nvdb(const std::string& path, const std::vector<TestVdbGrid>& grids, bool zip) {
  openvdb::initialize();
  std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> handles;
  for (const TestVdbGrid& g : grids)
    handles.push_back(nanovdb::openToNanoVDB(*openvdb_grid(g), nanovdb::StatsMode::Default,
                                             nanovdb::ChecksumMode::Full));
  nanovdb::io::writeGrids(path, handles, zip ? nanovdb::io::Codec::ZIP : nanovdb::io::Codec::NONE);
}

void write_vec3_nvdb(const std::string& path, const std::string& name) {
  openvdb::initialize();
  openvdb::Vec3SGrid::Ptr grid = openvdb::Vec3SGrid::create();
  grid->setName(name);
  grid->getAccessor().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 2, 3));
  nanovdb::io::writeGrid(path, nanovdb::openToNanoVDB(*grid));
}

void write_vec3_vdb(const std::string& path, const std::string& name) {
  openvdb::initialize();
  openvdb::Vec3SGrid::Ptr grid = openvdb::Vec3SGrid::create();
  grid->setName(name);
  grid->getAccessor().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 2, 3));
  openvdb::io::File(path).write({grid});
}

struct VdbSampler::Impl {
  openvdb::FloatGrid::Ptr grid;
};

VdbSampler::VdbSampler(const std::string& path, const std::string& name) {
  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  auto impl = std::make_shared<Impl>();
  impl->grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
  file.close();
  impl_ = impl;
}

double VdbSampler::operator()(const Eigen::Vector3d& world) const {
  const openvdb::Vec3d index =
      impl_->grid->transform().worldToIndex(openvdb::Vec3d(world.x(), world.y(), world.z()));
  return openvdb::tools::BoxSampler::sample(impl_->grid->tree(), index);
}

}  // namespace kasha::test
