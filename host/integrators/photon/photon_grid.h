#pragma once
// Photon mapping's hashed grid on the device (kernels/photon_gather.cl): its cell size from the
// pass's gather radii, built over a full store by counting sort — photons per cell, each cell's
// end by a prefix sum, each photon's place in its cell's run, each run sorted by the photons'
// keys so the gather sums in one order — and the gather of every visible point through it.
#include <cstddef>

#include "render/kernel_launcher.h"

namespace kasha {

// Bytes the grid keeps per store record: its cell and its sorted index.
constexpr size_t kGridBytesPerRecord = 2 * sizeof(cl_int);

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

  size_t bytes(size_t capacity) const {
    return cells_ * 2 * sizeof(float) + capacity * kGridBytesPerRecord;
  }

 private:
  KernelLauncher& device_;
  size_t cells_;
  cl::Kernel cell_size_kernel_, count_kernel_, scan_kernel_, scatter_kernel_, sort_kernel_,
      gather_kernel_;
  cl::Buffer cell_, cell_count_, cell_end_, photon_cell_, sorted_;
};

}  // namespace kasha
