#pragma once
// Density grids from OpenVDB files (docs/media.md#openvdb-grids): one float grid of a .vdb file as
// a DensityGrid that reconstructs it as OpenVDB's trilinear BoxSampler does (exactly where the
// voxels beyond the active ones hold the background, as a fog volume's do).
#include <string>

#include "scene/medium.h"

namespace kasha {

// The float grid `grid_name` of the .vdb file at `path` (`shown`: the name messages give it).
// Its active voxels' bounding box, one background voxel wider on every side, becomes the samples;
// p0 and p1 are that box in index space and to_world the grid's index-to-world map. Refused with
// one line: an unreadable file, no such grid, a grid that is not a float fog volume, a background
// other than 0, a negative or non-finite value, a map that is not affine, over 2^28 samples.
DensityGrid read_vdb_density(const std::string& path, const std::string& shown,
                             const std::string& grid_name);

// The float grid `grid_name` of a .vdb or .nvdb file on the samples of `lattice`, a grid read by
// read_vdb_density whose file_map the grid must share (a temperature beside a density). Refused
// with one line as above, and where the maps differ or a value is not finite.
std::vector<float> read_vdb_on_lattice(const std::string& path, const std::string& shown,
                                       const std::string& grid_name, const DensityGrid& lattice);

// Whether the .vdb file at `path` holds a grid named `grid_name` (false where it cannot be read).
bool vdb_has_grid(const std::string& path, const std::string& grid_name);

}  // namespace kasha
