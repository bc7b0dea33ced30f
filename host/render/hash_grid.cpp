#include "render/hash_grid.h"

#include "opencl/device_buffer.h"

namespace kasha {

HashGrid::HashGrid(KernelLauncher& device, const cl::Program& program, size_t capacity, bool placed)
    : device_(device),
      placing_(placed),
      count_kernel_(program, "grid_count"),
      scan_kernel_(program, "grid_scan"),
      scatter_kernel_(program, "grid_scatter"),
      sort_kernel_(program, "grid_sort_cells") {
  // About one cell per record: hash collisions stay rare without the table outgrowing them.
  cells_ = 1024;
  while (cells_ < capacity && cells_ < (1u << 22)) cells_ *= 2;
  ClContext& cl = device.cl();
  cell_count_ = device_buffer(cl, cells_ * sizeof(cl_int), "hashed grid: its cells");
  cell_end_ = device_buffer(cl, cells_ * sizeof(cl_int), "hashed grid: its cells");
  record_cell_ = device_buffer(cl, capacity * sizeof(cl_uint), "hashed grid: its records");
  sorted_ = device_buffer(cl, capacity * sizeof(cl_int), "hashed grid: its records");
  if (placed) {
    place_kernel_ = cl::Kernel(program, "grid_place");
    placed_ = device_buffer(cl, capacity * sizeof(cl_float4), "hashed grid: its records' places");
  }
}

void HashGrid::build(const cl::Buffer& store, size_t count, const cl::Buffer& cell) {
  device_.cl().queue().enqueueFillBuffer(cell_count_, cl_int(0), 0, cells_ * sizeof(cl_int));
  if (count > 0)
    device_.launch_own(count_kernel_, count, store, cell, mask(), cell_count_, record_cell_);
  device_.launch_own_range(scan_kernel_, 0, device_.work_group_size(scan_kernel_), cell_count_,
                           static_cast<cl_int>(cells_), cell_end_);
  if (count > 0) device_.launch_own(scatter_kernel_, count, record_cell_, cell_end_, sorted_);
  device_.launch_own(sort_kernel_, cells_, store, cell_count_, cell_end_, sorted_);
  if (placing_ && count > 0) device_.launch_own(place_kernel_, count, store, sorted_, cell_end_, mask(), placed_);
}

}  // namespace kasha
