#include "integrators/photon/photon_grid.h"

#include "opencl/device_buffer.h"

namespace kasha {

PhotonGrid::PhotonGrid(KernelLauncher& device, const cl::Program& program, size_t capacity)
    : device_(device),
      cell_size_kernel_(program, "grid_cell_size"),
      count_kernel_(program, "grid_count"),
      scan_kernel_(program, "grid_scan"),
      scatter_kernel_(program, "grid_scatter"),
      sort_kernel_(program, "grid_sort_cells"),
      gather_kernel_(program, "gather_photons") {
  // About one cell per record: hash collisions stay rare without the table outgrowing them.
  cells_ = 1024;
  while (cells_ < capacity && cells_ < (1u << 22)) cells_ *= 2;
  ClContext& cl = device.cl();
  cell_ = device_buffer(cl, 2 * sizeof(cl_float), "photon: the grid's cell size");
  cell_count_ = device_buffer(cl, cells_ * sizeof(cl_int), "photon: the grid's cells");
  cell_end_ = device_buffer(cl, cells_ * sizeof(cl_int), "photon: the grid's cells");
  photon_cell_ = device_buffer(cl, capacity * sizeof(cl_uint), "photon: the grid's photons");
  sorted_ = device_buffer(cl, capacity * sizeof(cl_int), "photon: the grid's photons");
}

void PhotonGrid::size_cells(const cl::Buffer& visible_points, const cl::Buffer& radius,
                            size_t pixels) {
  device_.launch_own_range(cell_size_kernel_, 0, device_.work_group_size(cell_size_kernel_),
                           visible_points, radius, static_cast<cl_int>(pixels), cell_);
}

void PhotonGrid::gather(const cl::Buffer& store, size_t count, const cl::Buffer& visible_points,
                        const cl::Buffer& radius, cl::Buffer& flux, cl::Buffer& found) {
  const cl_uint mask = static_cast<cl_uint>(cells_ - 1);
  device_.cl().queue().enqueueFillBuffer(cell_count_, cl_int(0), 0, cells_ * sizeof(cl_int));
  device_.launch_own(count_kernel_, count, store, cell_, mask, cell_count_, photon_cell_);
  device_.launch_own_range(scan_kernel_, 0, device_.work_group_size(scan_kernel_), cell_count_,
                           static_cast<cl_int>(cells_), cell_end_);
  device_.launch_own(scatter_kernel_, count, photon_cell_, cell_end_, sorted_);
  device_.launch_own(sort_kernel_, cells_, store, cell_count_, cell_end_, sorted_);
  device_.launch_own(gather_kernel_, device_.film().pixels(), device_.film().cmf_buffer(),
                     visible_points, radius, store, sorted_, cell_count_, cell_end_, cell_, mask,
                     flux, found);
}

}  // namespace kasha
