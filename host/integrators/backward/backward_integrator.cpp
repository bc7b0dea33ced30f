// `--integrator backward`: the OpenCL camera path tracer of kernels/backward/backward.cl
// (docs/design.md#backward-transport). A pass is `spp` paths per pixel; the kernel's work items own
// their pixels and add to the film's per-pixel sums, over launches of bounded work.
#include <algorithm>
#include <chrono>

#include "opencl/device_buffer.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "shared/launch_records.h"

namespace kasha {

constexpr int kBackwardSpp = 16;  // camera paths a pixel per pass unless --spp says

class BackwardIntegrator : public KernelIntegrator {
 public:
  explicit BackwardIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(
            s, "backward/backward.cl",
            s.hooks.full_matrix ? KernelDefines{{"KASHA_FULL_MATRIX", "1"}} : KernelDefines{}),
        spp_(s.settings.spp > 0 ? s.settings.spp : kBackwardSpp),
        seed_(s.settings.seed),
        kernel_(program_, "render_backward"),
        rejected_(device_buffer(cl_, film_.pixels() * sizeof(cl_int), "backward: rejected counts")),
        cut_(device_buffer(cl_, film_.pixels() * sizeof(cl_float),
                           "backward: depth-guard tallies")) {}

  PassResult render_pass(int pass) override {
    film_.clear_pixel_sums();
    cl_.queue().enqueueFillBuffer(rejected_, cl_int(0), 0, film_.pixels() * sizeof(cl_int));
    cl_.queue().enqueueFillBuffer(cut_, cl_float(0), 0, film_.pixels() * sizeof(cl_float));
    // Launches of bounded work: whole sample slices over every pixel while one fits the pacer's
    // size, else one sample over a range of pixels; the pass stops between launches on the
    // deadline or Ctrl-C, so only the last slice's pixels can differ by a sample.
    const size_t pixels = film_.pixels();
    const double total = static_cast<double>(pixels) * spp_;
    double work = 0;
    int k = 0;         // the next sample slice starts here
    size_t first = 0;  // and, within a one-sample slice, at this pixel
    while (k < spp_) {
      if (work > 0 && control_.stop_now()) break;
      size_t units = pacer_.next(static_cast<size_t>(total - work));
      int samples = 1;
      size_t count = std::min(units, pixels - first);
      if (first == 0 && units >= pixels)
        samples = static_cast<int>(std::min<size_t>(units / pixels, spp_ - k));
      auto t0 = std::chrono::steady_clock::now();
      const KBackwardLaunch record{spp_, k, k + samples, seed_, static_cast<uint>(pass)};
      launch_range(kernel_, first, count, film_.pixel_sums(), rejected_, cut_, record);
      pacer_.record(count * samples, seconds_since(t0));
      work += static_cast<double>(count) * samples;
      first += count;
      if (first == pixels) first = 0, k += samples;
      control_.report(work / total);
    }
    PassResult r{pass, k, {}, film_.read_pixel_sums(), work / total, {}, {}};
    if (k < spp_) {
      r.pixel_samples.assign(pixels, k);
      for (size_t p = 0; p < first; ++p) ++r.pixel_samples[p];
    }
    r.counters.rejected_samples = read_sum<cl_int>(rejected_, film_.pixels());
    r.counters.depth_guard.cut = read_sum<cl_float>(cut_, film_.pixels());  // relative to a start
    r.counters.depth_guard.of = work;
    add_ray_counts(r);
    return r;
  }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels()) * spp_;
  }
  long long photons_per_pass() const override { return 0; }
  std::map<std::string, size_t> device_buffers() const override {
    return {{"film sums", film_.pixels() * film_.rows() * sizeof(float)},
            {"rejected counts", film_.pixels() * sizeof(cl_int)}};
  }

 private:
  int spp_;
  unsigned seed_;
  LaunchPacer pacer_;  // in pixel samples
  cl::Kernel kernel_;
  cl::Buffer rejected_, cut_;
};

KASHA_REGISTER_INTEGRATOR(
    BackwardIntegrator, "backward",
    "camera paths with next-event estimation and MIS, diagonal/rank-1 path colour",
    {{"--spp", IntegratorOption::Value::integer, 1, 1 << 20, "camera samples per pixel per pass",
      std::to_string(kBackwardSpp), KASHA_SETTING(spp)}},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true,
                     /*sees camera mirrors*/ true, /*reference*/ true});

}  // namespace kasha
