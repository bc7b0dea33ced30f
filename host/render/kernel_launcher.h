#pragma once
// Kernel launches on one device, as every OpenCL integrator and its parts (photon mapping's
// store and grid) make them: the scene's and the film's parameters (KASHA_SCENE_PARAMS,
// KASHA_FILM_PARAMS) bound before the kernel's own arguments, or (launch_own) only its own, for
// kernels that read neither and trace no rays; the range in whole work-groups; the time counted.
#include <chrono>
#include <vector>

#include "film/pass_result.h"
#include "opencl/device.h"
#include "render/device_film.h"
#include "render/device_scene.h"

namespace kasha {

class KernelLauncher {
 public:
  KernelLauncher(ClContext& cl, DeviceScene& scene, DeviceFilm& film)
      : cl_(cl), scene_(scene), film_(film) {}

  ClContext& cl() { return cl_; }
  const DeviceScene& scene() const { return scene_; }
  DeviceFilm& film() { return film_; }
  // Seconds spent in launches so far (enqueue to finish): the rest of a pass is the host's.
  double launched_seconds() const { return device_seconds_; }

  // Sets the scene's and the film's parameters, then `args` in order; enqueues `items` work items.
  template <typename... Args>
  void launch(cl::Kernel& kernel, size_t items, const Args&... args) {
    launch_items(kernel, true, 0, items, args...);
  }

  // The same for work items [first, first + count), and waits for them: passes are split into
  // such launches of bounded work (render/launch_pacer.h). The range is rounded up to whole
  // work-groups of a fixed size, and the kernel's last two arguments (`item_first`, `item_end`,
  // kernels/shared/launch_range.h) give its items and tell the extra ones to return: PoCL compiles
  // a work-group function per local size and another for a non-zero global offset, so every
  // launch has offset 0 and one local size.
  template <typename... Args>
  void launch_range(cl::Kernel& kernel, size_t first, size_t count, const Args&... args) {
    launch_items(kernel, true, first, count, args...);
  }

  // launch and launch_range for kernels that take neither the scene's nor the film's parameters:
  // only `args`, then `item_first` and `item_end`.
  template <typename... Args>
  void launch_own(cl::Kernel& kernel, size_t items, const Args&... args) {
    launch_items(kernel, false, 0, items, args...);
  }
  template <typename... Args>
  void launch_own_range(cl::Kernel& kernel, size_t first, size_t count, const Args&... args) {
    launch_items(kernel, false, first, count, args...);
  }

  // 64 work items a group, or what the device allows for this kernel.
  size_t work_group_size(cl::Kernel& kernel);

  // The sum of the first `count` values of type T in a device buffer (per-pixel or per-item
  // counters a kernel wrote).
  template <typename T>
  double read_sum(const cl::Buffer& buffer, size_t count) {
    std::vector<T> values(count);
    cl_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(T), values.data());
    double sum = 0;
    for (T v : values) sum += v;
    return sum;
  }

  // The first `count` floats of a device buffer.
  void read_floats(const cl::Buffer& buffer, size_t count, std::vector<float>& out) {
    out.resize(count);
    cl_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
  }

  // The rays the pass's launches traced, added to its counters: every pass result carries them,
  // read from the job's counters (kernels/geometry/hit_point.h, add_ray_counts).
  void add_ray_counts(PassResult& result) {
    DeviceFilm::RayCounts rays = film_.take_ray_counts();
    result.counters.closest_rays += rays.closest;
    result.counters.shadow_rays += rays.shadow;
  }

 protected:
  ClContext& cl_;
  DeviceScene& scene_;
  DeviceFilm& film_;
  double device_seconds_ = 0;

 private:
  // The one launch path: the scene's and the film's parameters first if `views`, then `args`,
  // item_first and item_end; enqueues the range in whole work-groups, waits, and counts the time.
  template <typename... Args>
  void launch_items(cl::Kernel& kernel, bool views, size_t first, size_t count,
                    const Args&... args) {
    const auto start = std::chrono::steady_clock::now();
    const size_t local = work_group_size(kernel);
    const size_t global = (count + local - 1) / local * local;
    cl_uint a =
        views ? static_cast<cl_uint>(film_.bind(kernel, scene_.bind(kernel, 0, global))) : 0;
    (kernel.setArg(a++, args), ...);
    kernel.setArg(a++, static_cast<cl_int>(first));
    kernel.setArg(a, static_cast<cl_int>(first + count));
    cl_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global),
                                     cl::NDRange(local));
    cl_.queue().finish();
    device_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

}  // namespace kasha
