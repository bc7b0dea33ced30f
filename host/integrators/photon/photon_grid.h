#pragma once
// Photon mapping's gather on the device (kernels/photon/photon_gather.cl): the hashed grid's cell
// size from the pass's gather radii, the grid over a full store (render/hash_grid.h), and the
// gather of every visible point through it.
#include <cstddef>

#include "render/hash_grid.h"
#include "render/kernel_launcher.h"

namespace kasha {

class PhotonGrid {
 public:
  // A hash table of about one cell per record of a store of `capacity`.
  PhotonGrid(KernelLauncher& device, const cl::Program& program, size_t capacity);

  // The cell size for this pass's visible points and radii (the largest radius, on the device).
  void size_cells(const cl::Buffer& visible_points, const cl::Buffer& radius, size_t pixels);
  // The cell size as two floats: copied to the other devices with the visible points.
  cl::Buffer& cell() { return cell_; }

  // Builds the grid over the first `count` records of `store` and adds each visible point's
  // gather within its radius to `flux` (pixels × rows) and `found` (pixels).
  void gather(const cl::Buffer& store, size_t count, const cl::Buffer& visible_points,
              const cl::Buffer& radius, cl::Buffer& flux, cl::Buffer& found);

  size_t bytes(size_t capacity) const { return grid_.bytes(capacity); }

 private:
  KernelLauncher& device_;
  HashGrid grid_;
  cl::Kernel cell_size_kernel_, gather_kernel_;
  cl::Buffer cell_;
};

}  // namespace kasha
