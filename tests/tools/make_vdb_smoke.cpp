// Writes the grids of scenes/pbrt/vdb_smoke.pbrt and vdb_fire.pbrt (a density and a temperature)
// as an OpenVDB file and as the zipped NanoVDB file those scenes name (pbrt-v4's nanovdb medium
// reads only NanoVDB); pbrt-v4's renders are tests/data/pbrt-v4/vdb_{smoke,fire}.exr
// (tests/data/SOURCES.md). Not built by CMake (a one-off); with
// Debian's libopenvdb-dev and libnanovdb-dev:
//
//   g++ -std=c++17 -O2 -DNANOVDB_USE_ZIP tests/tools/make_vdb_smoke.cpp \
//     -DOPENVDB_ABI_VERSION_NUMBER=10 -lopenvdb -ltbb -lImath-3_1 -lz -o make_vdb_smoke
//   ./make_vdb_smoke vdb_smoke.vdb scenes/pbrt/vdb_smoke.nvdb
//
// The smoke is scripts/make_pbrt_smoke.py's lopsided, rippled blob, sampled at the voxels of a
// 41 × 41 × 41 lattice 0.025 apart, turned 12° about x by the file's own map; voxels below 0.002
// stay inactive, so the grid is sparse and fades out to nothing at its edges.
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

double smoke(double x, double y, double z) {  // x, y, z in the unit cube
  const double r2 = std::pow(x - 0.45, 2) + 2 * std::pow(y - 0.4, 2) + 0.7 * std::pow(z - 0.55, 2);
  return std::max(0.0, 2.5 * std::exp(-r2 / 0.05) * (1 + 0.6 * std::sin(11 * x + 4 * z + 3 * y)));
}

// The smoke's temperature in the grid's units (scenes/pbrt/vdb_fire.pbrt makes them kelvin): hot
// low in the middle, cooling upwards and outwards.
double heat(double x, double y, double z) {
  return 3.2 - 2.6 * y - 2.5 * (std::pow(x - 0.45, 2) + std::pow(z - 0.55, 2));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_vdb_smoke OUT.vdb OUT.nvdb\n");
    return 2;
  }
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::math::Transform::Ptr map = openvdb::math::Transform::createLinearTransform(0.025);
  map->postRotate(12 * M_PI / 180, openvdb::math::X_AXIS);
  grid->setTransform(map);
  // A temperature on the same voxels (scenes/pbrt/vdb_fire.pbrt; vdb_smoke.pbrt sets Lescale 0).
  openvdb::FloatGrid::Ptr temperature = openvdb::FloatGrid::create(0.0f);
  temperature->setName("temperature");
  temperature->setTransform(map);
  openvdb::FloatGrid::Accessor at = grid->getAccessor(), hot = temperature->getAccessor();
  int active = 0;
  for (int k = -20; k <= 20; ++k)
    for (int j = 0; j <= 40; ++j)
      for (int i = -20; i <= 20; ++i) {
        const double x = 0.5 + i / 40.0, y = j / 40.0, z = 0.5 + k / 40.0, v = smoke(x, y, z);
        if (v < 0.002) continue;
        at.setValue(openvdb::Coord(i, j, k), static_cast<float>(v));
        hot.setValue(openvdb::Coord(i, j, k), static_cast<float>(std::max(0.0, heat(x, y, z))));
        ++active;
      }
  openvdb::io::File(argv[1]).write({grid, temperature});
  std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> handles;
  handles.push_back(nanovdb::openToNanoVDB(*grid));
  handles.push_back(nanovdb::openToNanoVDB(*temperature));
  nanovdb::io::writeGrids(argv[2], handles, nanovdb::io::Codec::ZIP);
  std::printf("%d active voxels\n", active);
  return 0;
}
