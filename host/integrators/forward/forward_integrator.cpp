// `--integrator forward`: light tracing of kernels/forward.cl (DESIGN §2.1). A pass traces
// `photons` photons carrying the lights' total power; their splats, added in 64-bit fixed point
// (exact, so independent of the order work items run in), are one estimate of the image.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "spectral_product.h"

namespace kasha {

class ForwardIntegrator : public KernelIntegrator {
 public:
  explicit ForwardIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "forward.cl"),
        photons_(s.settings.photons),
        seed_(s.settings.seed),
        max_depth_(s.settings.max_depth),
        photons_per_item_(s.settings.photons_per_item),
        items_((photons_ + photons_per_item_ - 1) / photons_per_item_) {
    if (photons_ > (1LL << 31) - 1) throw Error("--photons: at most 2^31 - 1 photons per pass");
    kernel_ = cl::Kernel(program_, "trace_forward");
    // Fixed point: the brightest emitter's film value maps to 2^32, leaving 2^31 of headroom per
    // pixel and pass and a resolution of 2^-32 of it.
    double brightest = 0;
    const std::vector<float>& le = scene_.data().emitter_radiance;
    const std::vector<float>& cmf = film_.cmf();
    const int n = s.scene.grid.bins;
    for (size_t e = 0; e * n < le.size(); ++e)
      for (int r = 0; r < film_.rows(); ++r)
        brightest = std::max(
            brightest, film_row(cmf.data(), film_.spectral(), n, r, nullptr, &le[e * n], nullptr));
    film_scale_ = static_cast<float>(std::ldexp(1.0, 32) / std::max(brightest, 1e-30));
    fixed_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, cells() * sizeof(cl_long));
    stats_ = cl::Buffer(cl_.context(), CL_MEM_WRITE_ONLY, items_ * 4 * sizeof(float));
    overflow_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, sizeof(cl_int));
  }

  PassResult render_pass(int pass) override {
    cl_.queue().enqueueFillBuffer(fixed_, cl_long(0), 0, cells() * sizeof(cl_long));
    cl_.queue().enqueueFillBuffer(overflow_, cl_int(0), 0, sizeof(cl_int));
    cl_.queue().enqueueFillBuffer(stats_, cl_float(0), 0, items_ * 4 * sizeof(float));
    // Launches of bounded work; a pass cut short (deadline, Ctrl-C) is the estimate of the photons
    // it traced, scaled up to the pass's photons (each carries 1/photons of the power).
    size_t done = 0;
    while (done < items_) {
      if (done > 0 && control_.stop_now()) break;
      size_t n = pacer_.next(items_ - done);
      auto t0 = std::chrono::steady_clock::now();
      launch_range(kernel_, done, n, static_cast<cl_int>(photons_), photons_per_item_, max_depth_,
                   fixed_, film_scale_, stats_, overflow_, seed_, static_cast<cl_uint>(pass));
      pacer_.record(n, seconds_since(t0));
      done += n;
      control_.report(static_cast<double>(done) / items_);
    }
    const double traced = std::min<double>(static_cast<double>(done) * photons_per_item_,
                                           static_cast<double>(photons_));
    const double scale_up = photons_ / traced;

    std::vector<cl_long> fixed(cells());
    std::vector<float> stats(items_ * 4);
    cl_int overflow = 0;
    cl_.queue().enqueueReadBuffer(fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_long), fixed.data());
    cl_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, stats.size() * sizeof(float), stats.data());
    cl_.queue().enqueueReadBuffer(overflow_, CL_TRUE, 0, sizeof(cl_int), &overflow);
    PassResult r;
    r.pass = pass;
    r.samples = 1;  // the pass's splats are one estimate of every pixel
    r.fraction = traced / photons_;
    r.sums.resize(fixed.size());
    for (size_t i = 0; i < fixed.size(); ++i)
      r.sums[i] = fixed[i] / static_cast<double>(film_scale_) * scale_up;
    double power[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < items_; ++i)
      for (int k = 0; k < 4; ++k) power[k] += stats[4 * i + k] * scale_up;
    r.tallies = {{"rejected samples", overflow},
                 {"power emitted (W)", power[0]},
                 {"power absorbed (W)", power[1]},
                 {"power escaped (W)", power[2]},
                 {"power in flight (W)", power[3]},
                 {kDepthGuardCut, power[3]},  // photons the depth guard cut, still carrying power
                 {kDepthGuardOf, power[0]}};
    return r;
  }

  long long camera_paths_per_pass() const override { return 0; }
  long long photons_per_pass() const override { return photons_; }
  std::map<std::string, size_t> device_buffers() const override {
    return {{"fixed-point film", cells() * sizeof(cl_long)},
            {"power ledger", items_ * 4 * sizeof(float)}};
  }

 private:
  size_t cells() const { return film_.pixels() * film_.rows(); }

  long long photons_;
  unsigned seed_;
  int max_depth_, photons_per_item_;
  size_t items_;
  float film_scale_;
  LaunchPacer pacer_{0.2, 16};  // in work items
  cl::Kernel kernel_;
  cl::Buffer fixed_, stats_, overflow_;
};

KASHA_REGISTER_INTEGRATOR(
    ForwardIntegrator, "forward",
    "light tracing: photons from the lights splatted to the camera, constant-energy branching",
    {"--photons"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true,
                     /*sees camera mirrors*/ false, /*reference*/ false});

}  // namespace kasha
