// `--integrator forward`: light tracing of kernels/forward/forward.cl
// (docs/design.md#forward-transport). A pass traces `photons` photons carrying the lights' total
// power; their splats, added in 128-bit fixed point (render/fixed_point_film.h: exact, so
// independent of the order work items run in), are one estimate of the image.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "opencl/device_buffer.h"
#include "render/depth_cap.h"
#include "render/fixed_point_film.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "shared/launch_records.h"

namespace kasha {

constexpr long long kForwardPhotons = 1 << 18;  // photons per pass unless --photons says

class ForwardIntegrator : public KernelIntegrator {
 public:
  explicit ForwardIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "forward/forward.cl"),
        photons_(s.settings.photons > 0 ? s.settings.photons : kForwardPhotons),
        seed_(s.settings.seed),
        max_depth_(s.settings.depth_guard),
        photons_per_item_(s.hooks.photons_per_item),
        items_((photons_ + photons_per_item_ - 1) / photons_per_item_) {
    if (photons_ > (1LL << 31) - 1) throw Error("--photons: at most 2^31 - 1 photons per pass");
    // A photon's hit k is a path of k + 1 scattering vertices: a cap N keeps hits 0 … N − 1, and
    // what it stops is the cap's doing, not the guard's.
    const int cap = depth_cap(s.settings, s.scene);
    if (cap != IntegratorSettings::kNoDepthCap && cap < max_depth_) {
      max_depth_ = cap;
      guarded_ = false;
    }
    kernel_ = cl::Kernel(program_, "trace_forward");
    film_shift_ = fixed_point_shift(scene_.data(), film_.cmf(), film_.spectral());
    fixed_ = device_buffer(cl_, cells() * 2 * sizeof(cl_ulong), "forward: the fixed-point film");
    stats_ = device_buffer(cl_, ledger_items() * 4 * sizeof(float), "forward: the power ledger");
    overflow_ = device_buffer(cl_, sizeof(cl_int), "forward: the rejected-sample counter");
  }

  PassResult render_pass(int pass) override {
    cl_.queue().enqueueFillBuffer(fixed_, cl_ulong(0), 0, cells() * 2 * sizeof(cl_ulong));
    cl_.queue().enqueueFillBuffer(overflow_, cl_int(0), 0, sizeof(cl_int));
    // Launches of bounded work; a pass cut short (deadline, Ctrl-C) is the estimate of the photons
    // it traced, scaled up to the pass's photons (each carries 1/photons of the power).
    size_t done = 0;
    double raw[4] = {0, 0, 0, 0};  // the launches' ledgers: emitted, absorbed, escaped, in flight
    while (done < items_) {
      if (done > 0 && control_.stop_now()) break;
      const size_t n = std::min(pacer_.next(items_ - done), ledger_items());
      auto t0 = std::chrono::steady_clock::now();
      const KForwardLaunch record{static_cast<int>(photons_),
                                  photons_per_item_,
                                  max_depth_,
                                  static_cast<int>(film_shift_),
                                  seed_,
                                  static_cast<uint>(pass)};
      launch_range(kernel_, done, n, record, fixed_, stats_, overflow_);
      pacer_.record(n, seconds_since(t0));
      add_ledger(n, raw);
      done += n;
      control_.report(static_cast<double>(done) / items_);
    }
    const double traced = std::min<double>(static_cast<double>(done) * photons_per_item_,
                                           static_cast<double>(photons_));
    const double scale_up = photons_ / traced;

    std::vector<cl_ulong> fixed(2 * cells());  // lo, hi per cell
    cl_int overflow = 0;
    cl_.queue().enqueueReadBuffer(fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_ulong),
                                  fixed.data());
    cl_.queue().enqueueReadBuffer(overflow_, CL_TRUE, 0, sizeof(cl_int), &overflow);
    PassResult r;
    r.pass = pass;
    r.samples = 1;  // the pass's splats are one estimate of every pixel
    r.fraction = traced / photons_;
    r.sums.resize(cells());
    for (size_t i = 0; i < cells(); ++i)
      r.sums[i] = fixed_point_value(fixed[2 * i], fixed[2 * i + 1], film_shift_) * scale_up;
    double power[4];
    for (int k = 0; k < 4; ++k) power[k] = raw[k] * scale_up;
    PassCounters& c = r.counters;
    c.rejected_samples = overflow;
    c.power_emitted_w = power[0];
    c.power_absorbed_w = power[1];
    c.power_escaped_w = power[2];
    c.power_in_flight_w = power[3];
    c.depth_guard = {guarded_ ? power[3] : 0, power[0]};  // photons the guard cut, still carrying
    add_ray_counts(r);
    return r;
  }

  long long camera_paths_per_pass() const override { return 0; }
  long long photons_per_pass() const override { return photons_; }
  std::map<std::string, size_t> device_buffers() const override {
    return {{"fixed-point film", cells() * 2 * sizeof(cl_ulong)},
            {"power ledger", ledger_items() * 4 * sizeof(float)}};
  }

 private:
  size_t cells() const { return film_.pixels() * film_.rows(); }
  // Work items a launch has at most: each keeps its power ledger (4 floats) until the launch's are
  // added up, so the ledger does not grow with --photons (1 MiB, where 2^31 photons took 512).
  static constexpr size_t kLedgerItems = 1 << 16;
  size_t ledger_items() const { return std::min<size_t>(items_, kLedgerItems); }

  // Adds the launch's `n` work items' ledgers to `raw`, in item order.
  void add_ledger(size_t n, double raw[4]) {
    std::vector<float> stats(n * 4);
    cl_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, stats.size() * sizeof(float), stats.data());
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 4; ++k) raw[k] += stats[4 * i + k];
  }

  long long photons_;
  unsigned seed_;
  int max_depth_, photons_per_item_;  // max_depth_: the hits a photon may have
  bool guarded_ = true;               // max_depth_ is the depth guard, not the --max-depth cap
  size_t items_;
  int film_shift_;             // a film value v is v·2^film_shift_ fixed-point units
  LaunchPacer pacer_{0.2, 4};  // in work items: the first launch is small, as paths may be long
  cl::Kernel kernel_;
  cl::Buffer fixed_, stats_, overflow_;
};

KASHA_REGISTER_INTEGRATOR(
    ForwardIntegrator, "forward",
    "light tracing: photons from the lights splatted to the camera, constant-energy branching",
    {{"--photons", IntegratorOption::Value::integer, 1, 2147483647, "photons per pass",
      number_text(kForwardPhotons), KASHA_SETTING(photons)}},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true, /*sees camera mirrors*/ false,
                     /*reference*/ false, /*direct by merges*/ false,
                     /*samples seen light*/ false, /*medium light paths*/ true});

}  // namespace kasha
