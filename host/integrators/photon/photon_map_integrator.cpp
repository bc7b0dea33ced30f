// `--integrator photon` (the default): bidirectional photon mapping, progressive as stochastic
// progressive photon mapping (Hachisuka & Jensen 2009). Each pass: a camera pass storing one
// visible point per pixel (kernels/photon_map.cl), a photon pass storing photons at Lambert hits,
// a kd-tree over them and a gather on the host (photon_gather.h). The pass's result is the
// directly seen emission and, per pixel, the gather's radius, count and flux; the film turns
// those into SPPM statistics (film/sppm_statistics.h). With edge correction (opt-in), each
// pass's flux is divided by the fraction of its gather disc on accepted surface (disc_coverage.h).
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "geometry/embree_scene.h"
#include "integrators/photon/disc_coverage.h"
#include "integrators/photon/photon_gather.h"
#include "integrators/photon/photon_records.h"
#include "opencl/device_buffer.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"

namespace kasha {

namespace {
constexpr int kPhotonsPerItem = 64;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

class PhotonMapIntegrator : public KernelIntegrator {
 public:
  explicit PhotonMapIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "photon_map.cl"),
        accumulated_(s.film),
        photons_(s.settings.photons),
        alpha_(s.settings.alpha),
        radius_(s.settings.radius),
        seed_(s.settings.seed),
        photon_floats_(KASHA_PHOTON_FLOATS(s.scene.grid.bins)),
        vp_floats_(KASHA_VP_FLOATS(s.scene.grid.bins, film_.rows(), s.scene.fluorescent())),
        layout_{s.scene.grid.bins, film_.rows(), film_.spectral(), s.scene.fluorescent(),
                film_.cmf().data()} {
    if (photons_ > (1LL << 31) - 1) throw Error("--photons: at most 2^31 - 1 photons per pass");
    if (!(alpha_ > 0 && alpha_ < 1)) throw Error("--alpha must lie in (0, 1)");
    photon_kernel_ = cl::Kernel(program_, "trace_photon_map");
    camera_kernel_ = cl::Kernel(program_, "camera_pass");
    counter_ = device_buffer(cl_, sizeof(cl_int), "photon: the store counter");
    cut_ =
        device_buffer(cl_, photon_items() * sizeof(cl_float),
                      "photon: the depth-guard tallies of --photons " + std::to_string(photons_));
    camera_cut_ = device_buffer(cl_, film_.pixels() * sizeof(cl_float),
                                "photon: the camera pass's depth-guard tallies");
    vps_ = device_buffer(cl_, vp_bytes(), "photon: the visible points of the image");
    // The store holds about four photons per emitted one (what a pass of ordinary albedos stores)
    // within the memory budget; passes that store more are gathered in batches, so memory stays
    // the same however long photon paths get.
    const size_t record = photon_floats_ * sizeof(float);
    const size_t budget = s.settings.memory > 0 ? static_cast<size_t>(s.settings.memory)
                                                : default_memory_budget(cl_.info());
    // At least 2^18 records, so a pass of few photons with long paths fills the store in
    // launches of many photons rather than one photon at a time.
    capacity_ =
        std::min<size_t>({std::max<size_t>(static_cast<size_t>(photons_) * 4 + 1024, 1u << 18),
                          budget / record, (1u << 31) - 1});
    if (capacity_ < 1)
      throw Error("--memory: " + std::to_string(budget) + " bytes hold no photon record (" +
                  std::to_string(record) + " bytes each)");
    store_ =
        device_buffer(cl_, capacity_ * record, "photon: the photon store (--memory, --photons)");
    const KCamera& c = scene_.data().camera;
    footprint_ =
        2.0 * std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]) / c.height;
    // Gather radii stay within a fiftieth of the scene's diagonal: one pixel of a tiny image
    // would otherwise gather over whole walls, biasing SPPM far beyond its first passes.
    Eigen::AlignedBox3d box;
    for (const KTriangle& t : s.scene.triangles)
      for (const float* v : {t.v0, t.v1, t.v2}) box.extend(Eigen::Vector3d(v[0], v[1], v[2]));
    max_radius_ = box.diagonal().norm() / 50;
    if (radius_ > max_radius_)
      warn("--radius " + std::to_string(radius_) +
           " is beyond 1/50 of the scene's diagonal; using " + std::to_string(max_radius_));
    if (s.settings.edge_correction) embree_ = std::make_unique<EmbreeScene>(s.scene.triangles);
  }

  PassResult render_pass(int pass) override {
    auto t0 = Clock::now();
    film_.clear_pixel_sums();
    launch(camera_kernel_, film_.pixels(), vps_, film_.pixel_sums(), camera_cut_, seed_,
           static_cast<cl_uint>(pass));
    vps_host_.resize(film_.pixels() * vp_floats_);
    cl_.queue().enqueueReadBuffer(vps_, CL_TRUE, 0, vp_bytes(), vps_host_.data());
    PassResult r{pass, 1, {}, film_.read_pixel_sums(), 1.0, GatherPass{}, {}};
    r.tallies["time: camera pass (s)"] = since(t0);

    GatherPass& g = *r.gather;
    g.alpha = alpha_;
    g.radius = initial_radii();
    g.flux.assign(film_.pixels() * film_.rows(), 0.0);
    g.found.assign(film_.pixels(), 0);
    const double traced = trace_and_gather(pass, g, r.tallies);
    // A pass cut short (deadline, Ctrl-C) estimates with the photons it traced: each carries
    // 1/photons of the lights' power, so their flux is scaled up to the pass's photons.
    r.fraction = traced / static_cast<double>(photons_);
    for (double& v : g.flux) v /= r.fraction;
    r.tallies[kDepthGuardOf] = traced;
    r.tallies[kCameraDepthGuardCut] = read_sum<cl_float>(camera_cut_, film_.pixels());
    r.tallies[kCameraDepthGuardOf] = static_cast<double>(film_.pixels());
    return r;
  }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels());
  }
  long long photons_per_pass() const override { return photons_; }
  std::map<std::string, size_t> device_buffers() const override {
    return {{"visible points", vp_bytes()},
            {"photon store", capacity_ * photon_floats_ * sizeof(float)},
            {"direct emission", film_.pixels() * film_.rows() * sizeof(float)}};
  }

 private:
  size_t vp_bytes() const { return film_.pixels() * vp_floats_ * sizeof(float); }
  size_t photon_items() const { return (photons_ + kPhotonsPerItem - 1) / kPhotonsPerItem; }

  // The radii this pass gathers within: the SPPM radius so far, or for a pixel's first visible
  // point --radius or one pixel's width at its distance, kept within the scene's bound.
  std::vector<double> initial_radii() const {
    std::vector<double> radius = accumulated_.photon_radius();
    radius.resize(film_.pixels(), 0.0);
    for (size_t p = 0; p < film_.pixels(); ++p) {
      const float* vp = &vps_host_[p * vp_floats_];
      if (radius[p] == 0 && vp[KASHA_VP_VALID] != 0) {
        const double pixel = footprint_ * vp[KASHA_VP_DISTANCE];
        radius[p] = std::min(radius_ > 0 ? radius_ : pixel, max_radius_);
        if (!(radius[p] > 0)) radius[p] = max_radius_;
        // A radius far below a pixel's footprint catches no photon for many passes.
        if (radius_ > 0 && radius_ < pixel / 100 && !warned_small_) {
          warned_small_ = true;
          warn("--radius " + std::to_string(radius_) +
               " is below 1/100 of a pixel's footprint at the visible points; using that");
        }
        if (radius_ > 0) radius[p] = std::max(radius[p], std::min(pixel / 100, max_radius_));
      }
    }
    return radius;
  }

  // Traces the pass's photons in launches of bounded time into the store, gathering each time
  // the store is full and at the end; stops early on the deadline or Ctrl-C. Returns the
  // photons traced.
  double trace_and_gather(int pass, GatherPass& g, std::map<std::string, double>& tallies) {
    size_t done = 0, stored = 0;  // photons traced, records in the store
    double per_photon = 4;        // records a photon stores, as measured so far
    double trace_s = 0, gather_s = 0, records = 0, cut = 0;
    auto gather_store = [&] {
      auto t = Clock::now();
      gather_batch(stored, g);
      gather_s += since(t);
      records += static_cast<double>(stored);
      stored = 0;
    };
    const size_t photons = static_cast<size_t>(photons_);
    while (done < photons) {
      if (done > 0 && control_.stop_now()) break;
      size_t n = pacer_.next(photons - done);
      // Leave room for what these photons will store, with a margin; else gather first.
      const size_t room = capacity_ - stored;
      const size_t fit = static_cast<size_t>(room / (per_photon * 1.25 + 1e-9));
      if (fit < std::min<size_t>(n, kPhotonsPerItem) && stored > 0) {
        gather_store();
        continue;
      }
      n = std::max<size_t>(1, std::min(n, fit));
      auto t = Clock::now();
      cl_int after = launch_photons(pass, done, n, 0, stored);
      trace_s += since(t);
      if (static_cast<size_t>(after) <= capacity_) {
        pacer_.record(n, since(t));
        per_photon = std::max(per_photon * 0.5, double(after - stored) / n);
        cut += read_sum<cl_float>(cut_, (n + kPhotonsPerItem - 1) / kPhotonsPerItem);
        stored = after;
        done += n;
        control_.report(static_cast<double>(done) / photons);
        continue;
      }
      // The launch overflowed: its stores beyond `stored` are incomplete and dropped.
      per_photon = std::max(per_photon, double(after - stored) / n);
      if (stored > 0) {
        gather_store();
      } else if (n > 1) {
        continue;  // fewer photons, as the new per-photon figure allows
      } else {
        // One photon stores more than the whole store: trace it again in segments.
        cut += trace_long_photon(pass, done, g, gather_s, records, trace_s);
        ++done;
      }
    }
    if (stored > 0) gather_store();
    tallies["time: photon tracing (s)"] = trace_s;
    tallies["time: kd-tree and gather (s)"] = gather_s;
    tallies["photons stored"] = records;
    tallies[kDepthGuardCut] = cut;  // per photon's start
    return static_cast<double>(done);
  }

  // Photons [first, first + count) into the store from slot `stored`, `skip` stores passed over
  // per photon; returns the store's count afterwards.
  cl_int launch_photons(int pass, size_t first, size_t count, int skip, size_t stored) {
    cl_int start = static_cast<cl_int>(stored);
    cl_.queue().enqueueWriteBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &start);
    const int per_item = count == 1 ? 1 : kPhotonsPerItem;
    launch_range(photon_kernel_, 0, (count + per_item - 1) / per_item,
                 static_cast<cl_int>(photons_), static_cast<cl_int>(first),
                 static_cast<cl_int>(count), per_item, skip, store_, counter_,
                 static_cast<cl_int>(capacity_), cut_, seed_, static_cast<cl_uint>(pass));
    cl_int after = 0;
    cl_.queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &after);
    if (after < 0) return static_cast<cl_int>(capacity_) + 1;  // wrapped: overflowed for sure
    return after;
  }

  // A photon whose stores exceed the store, traced again once per store-full of them (its path
  // is the same each time: its random numbers come from its index). Returns its depth-guard cut.
  double trace_long_photon(int pass, size_t index, GatherPass& g, double& gather_s, double& records,
                           double& trace_s) {
    double cut = 0;
    for (size_t skip = 0;; skip += capacity_) {
      if (skip > (1u << 31) - 1) throw Error("photon: one photon stored more than 2^31 records");
      auto t = Clock::now();
      cl_int after = launch_photons(pass, index, 1, static_cast<int>(skip), 0);
      trace_s += since(t);
      if (skip == 0) cut = read_sum<cl_float>(cut_, 1);
      const size_t batch = std::min<size_t>(static_cast<size_t>(after), capacity_);
      t = Clock::now();
      gather_batch(batch, g);
      gather_s += since(t);
      records += static_cast<double>(batch);
      if (static_cast<size_t>(after) <= capacity_) return cut;
      if (interrupt_requested()) return cut;  // the photon's remaining stores are lost; rare
    }
  }

  // Reads the first `count` stored photons back and adds their gather to g (its radii fixed).
  void gather_batch(size_t count, GatherPass& g) {
    if (count == 0) return;
    photons_host_.resize(count * photon_floats_);
    cl_.queue().enqueueReadBuffer(store_, CL_TRUE, 0, photons_host_.size() * sizeof(float),
                                  photons_host_.data());
    PhotonKdTree tree(photons_host_.data(), count, photon_floats_);
    GatherResult found =
        tree.gather(vps_host_.data(), vp_floats_, film_.pixels(), g.radius, layout_);
    if (embree_) {
      // A fresh rotation of the probe pattern each pass, so its stratification leaves no pattern.
      float rotation =
          static_cast<float>(2 * M_PI * std::fmod(0.6180339887 * (++batches_) + 1e-3 * seed_, 1.0));
      std::vector<float> coverage =
          disc_coverage(*embree_, vps_host_.data(), vp_floats_, film_.pixels(), g.radius, rotation);
      for (size_t p = 0; p < film_.pixels(); ++p)
        for (int k = 0; k < film_.rows(); ++k) found.flux[p * film_.rows() + k] /= coverage[p];
    }
    for (size_t i = 0; i < g.flux.size(); ++i) g.flux[i] += found.flux[i];
    for (size_t p = 0; p < g.found.size(); ++p) g.found[p] += found.found[p];
  }

  const Film& accumulated_;  // holds the SPPM radii the next gather uses
  long long photons_;
  double alpha_, radius_;
  unsigned seed_;
  int photon_floats_, vp_floats_;
  VertexFactorLayout layout_;
  double footprint_;   // pixel width on the image plane at unit distance
  double max_radius_;  // no gather radius beyond this
  mutable bool warned_small_ = false;
  size_t capacity_;  // photon records the store holds
  size_t batches_ = 0;
  LaunchPacer pacer_{0.2, 256};  // in photons: the first launch is small, as paths may be long
  std::vector<float> vps_host_, photons_host_;
  cl::Kernel photon_kernel_, camera_kernel_;
  cl::Buffer store_, counter_, vps_, cut_, camera_cut_;
  std::unique_ptr<EmbreeScene> embree_;  // probes the gather discs' coverage
};

KASHA_REGISTER_INTEGRATOR(
    PhotonMapIntegrator, "photon",
    "bidirectional photon mapping (SPPM): visible points with compact rank-1 factors, "
    "photons gathered on the host",
    {"--photons", "--alpha", "--radius", "--edge-correction", "--memory"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false});

}  // namespace kasha
