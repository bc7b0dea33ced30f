#pragma once
// The plumbing every OpenCL integrator shares: its program built for this scene and film, and
// launches that set the scene's and the film's parameters (KASHA_SCENE_PARAMS,
// KASHA_FILM_PARAMS) before the kernel's own arguments, or (launch_own) only its own arguments.
#include <chrono>
#include <string>
#include <vector>

#include "render/integrator_registry.h"

namespace kasha {

class KernelIntegrator : public Integrator {
 public:
  double device_seconds() const override { return device_seconds_; }
  std::string build_options() const override { return build_options_; }

 protected:
  // Builds kernels/<file> with the scene's definitions and `extra` ones.
  KernelIntegrator(const IntegratorSetup& setup, const std::string& file, KernelDefines extra = {});

  // Sets the scene's and the film's parameters, then `args` in order; enqueues `items` work items.
  template <typename... Args>
  void launch(cl::Kernel& kernel, size_t items, const Args&... args) {
    launch_range(kernel, 0, items, args...);
  }

  // The same for work items [first, first + count) (get_global_id counts from `first`), and waits
  // for them: passes are split into such launches of bounded work (render/launch_pacer.h). The
  // range is rounded up to whole work-groups of a fixed size, and the kernel's last argument
  // (`item_end`) tells the extra items to return: PoCL compiles a work-group function per local
  // size, so launches of varying sizes must not each choose their own.
  template <typename... Args>
  void launch_range(cl::Kernel& kernel, size_t first, size_t count, const Args&... args) {
    launch_items(kernel, true, first, count, args...);
  }

  // launch and launch_range for kernels that take neither the scene's nor the film's parameters
  // (they read neither and trace no rays): only `args`, then `item_end`.
  template <typename... Args>
  void launch_own(cl::Kernel& kernel, size_t items, const Args&... args) {
    launch_own_range(kernel, 0, items, args...);
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

  // The rays the pass's launches traced, as tallies (kClosestRays, kShadowRays): every pass
  // result carries them, read from the job's counters (kernels/hit_point.h, add_ray_counts).
  void add_ray_tallies(PassResult& result) {
    DeviceFilm::RayCounts rays = film_.take_ray_counts();
    result.tallies[kClosestRays] += rays.closest;
    result.tallies[kShadowRays] += rays.shadow;
  }

  // Seconds spent in launches so far (enqueue to finish): the rest of a pass is the host's.
  double device_seconds_ = 0;
  std::string build_options_;
  ClContext& cl_;
  DeviceScene& scene_;
  DeviceFilm& film_;
  cl::Program program_;

 private:
  // The one launch path: the scene's and the film's parameters first if `views`, then `args` and
  // item_end; enqueues the range in whole work-groups, waits, and counts the time.
  template <typename... Args>
  void launch_items(cl::Kernel& kernel, bool views, size_t first, size_t count, const Args&... args) {
    const auto start = std::chrono::steady_clock::now();
    cl_uint a = views ? static_cast<cl_uint>(film_.bind(kernel, scene_.bind(kernel, 0))) : 0;
    (kernel.setArg(a++, args), ...);
    kernel.setArg(a, static_cast<cl_int>(first + count));
    const size_t local = work_group_size(kernel);
    cl_.queue().enqueueNDRangeKernel(kernel, first > 0 ? cl::NDRange(first) : cl::NullRange,
                                     cl::NDRange((count + local - 1) / local * local),
                                     cl::NDRange(local));
    cl_.queue().finish();
    device_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

}  // namespace kasha
