#pragma once
// OpenVDB (and NanoVDB) files written for the VDB medium tests and the fuzz harness's seeds, and
// OpenVDB's own trilinear sampler as the truth to test kasha's reconstruction against.
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace kasha::test {

// One float grid's active voxels: values[(z * ny + y) * nx + x] at index origin + (x, y, z); a
// value of exactly 0 leaves its voxel inactive (the background, 0).
struct TestVdbGrid {
  std::string name = "density";
  std::array<int, 3> origin{0, 0, 0}, size{1, 1, 1};
  std::vector<float> values;
  Eigen::Affine3d index_to_world = Eigen::Affine3d::Identity();
  bool level_set = false;  // marks the grid a level set (kasha refuses those)
  float background = 0;
};

// Writes the grids to one .vdb file.
void write_vdb(const std::string& path, const std::vector<TestVdbGrid>& grids);
// Writes the grids to one NanoVDB .nvdb file (pbrt-v4's), with full checksums, zipped or not.
void write_nvdb(const std::string& path, const std::vector<TestVdbGrid>& grids, bool zip = false);
// Writes a NanoVDB grid of 3-vectors named `name`.
void write_vec3_nvdb(const std::string& path, const std::string& name);
// Writes a grid of 3-vectors named `name` (kasha reads float grids only).
void write_vec3_vdb(const std::string& path, const std::string& name);

// The named float grid of a .vdb file as OpenVDB samples it (tools::BoxSampler: trilinear in index
// space) at world points.
class VdbSampler {
 public:
  VdbSampler(const std::string& path, const std::string& name);
  double operator()(const Eigen::Vector3d& world) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace kasha::test
