#include "integrators/photon/photon_grid.h"

#include "opencl/device_buffer.h"

namespace kasha {

PhotonGrid::PhotonGrid(KernelLauncher& device, const cl::Program& program, size_t capacity)
    : device_(device),
      grid_(device, program, capacity),
      cell_size_kernel_(program, "grid_cell_size"),
      gather_kernel_(program, "gather_photons") {
  cell_ = device_buffer(device.cl(), 2 * sizeof(cl_float), "photon: the grid's cell size");
}

void PhotonGrid::size_cells(const cl::Buffer& visible_points, const cl::Buffer& radius,
                            size_t pixels) {
  device_.launch_own_range(cell_size_kernel_, 0, device_.work_group_size(cell_size_kernel_),
                           visible_points, radius, static_cast<cl_int>(pixels), cell_);
}

void PhotonGrid::gather(const cl::Buffer& store, size_t count, const cl::Buffer& visible_points,
                        const cl::Buffer& radius, cl::Buffer& flux, cl::Buffer& found) {
  grid_.build(store, count, cell_);
  device_.launch_own(gather_kernel_, device_.film().pixels(), device_.film().cmf_buffer(),
                     visible_points, radius, store, grid_.sorted(), grid_.cell_count(),
                     grid_.cell_end(), cell_, grid_.mask(), flux, found);
}

}  // namespace kasha
