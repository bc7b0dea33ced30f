#pragma once
// A hashed uniform grid over a store of records on the device (kernels/transport/hash_grid.cl):
// records counted per cell, each cell's end by a prefix sum, each record's place in its cell's run,
// each run sorted by the records' keys so that a query sums a cell in one order. Photon mapping's
// gather and vertex merging build one over their stores.
#include <cstddef>

#include "render/kernel_launcher.h"

namespace kasha {

// Bytes the grid keeps per store record: its cell and its sorted index.
constexpr size_t kGridBytesPerRecord = 2 * sizeof(cl_int);
// And with the records' positions placed in the grid's order (HashGrid::placed).
constexpr size_t kPlacedGridBytesPerRecord = kGridBytesPerRecord + sizeof(cl_float4);

class HashGrid {
 public:
  // A hash table of about one cell per record of a store of `capacity`; `placed`: it also keeps
  // the records' positions in its order (placed()).
  HashGrid(KernelLauncher& device, const cl::Program& program, size_t capacity,
           bool placed = false);

  // Builds the grid over the first `count` records of `store` with the cell size in `cell`
  // (size, 1/size: two floats on the device).
  void build(const cl::Buffer& store, size_t count, const cl::Buffer& cell);

  cl_uint mask() const { return static_cast<cl_uint>(cells_ - 1); }
  const cl::Buffer& cell_count() const { return cell_count_; }
  const cl::Buffer& cell_end() const { return cell_end_; }
  const cl::Buffer& sorted() const { return sorted_; }
  // Per sorted slot, float4: the record's position and its index as float bits (when asked for).
  const cl::Buffer& placed() const { return placed_; }
  size_t bytes(size_t capacity) const {
    return cells_ * 2 * sizeof(cl_int) +
           capacity * (placing_ ? kPlacedGridBytesPerRecord : kGridBytesPerRecord);
  }

 private:
  KernelLauncher& device_;
  size_t cells_;
  bool placing_;  // keeps placed()
  cl::Kernel count_kernel_, scan_kernel_, scatter_kernel_, sort_kernel_, place_kernel_;
  cl::Buffer cell_count_, cell_end_, record_cell_, sorted_, placed_;
};

}  // namespace kasha
