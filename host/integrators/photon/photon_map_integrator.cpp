// `--integrator photon` (the default): bidirectional photon mapping, progressive as stochastic
// progressive photon mapping (Hachisuka & Jensen 2009), the whole pass on the device
// (kernels/photon_map.cl, photon_gather.cl). Each pass: a camera pass — `--spp` paths per pixel
// with next-event estimation for direct light, the first storing the pixel's visible point — then
// photons traced into a store in launches of bounded time; each time the store is full, and at
// the end, a hashed grid is built over it by counting sort and every visible point gathers
// through it; then the per-pixel SPPM statistics are updated. Only the image crosses to the host,
// when it is wanted. `--gather host` gathers each store on the host instead (a nanoflann kd-tree
// on the host's threads, photon_gather.h), the statistics staying on the device.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
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
// Bytes a store record takes on the device beyond its floats: its cell and its sorted index.
constexpr size_t kGridBytesPerRecord = 2 * sizeof(cl_int);
}  // namespace

// Where a pass's stores are gathered: `--gather device|host`; `auto` is the device on every
// device type (measured on PoCL's CPU device too: README, "Photon mapping's pipeline").
bool gather_on_host(const std::string& gather) {
  if (gather == "host") return true;
  if (gather == "device" || gather == "auto") return false;
  throw Error("--gather " + gather + ": unknown (device, host or auto)");
}

// Probes per visible point and pass of the edge correction (disc_coverage in photon_gather.cl):
// few, as their ratio of sums averages over passes.
constexpr int kCoverageProbes = 4;

// Camera samples per pixel per pass unless --spp says: direct light, lamps seen directly and
// their edges converge with them while photon tracing dominates the pass (README).
constexpr int kDefaultCameraSamples = 8;

class PhotonMapIntegrator : public KernelIntegrator {
 public:
  explicit PhotonMapIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "photon_map.cl"),
        photons_(s.settings.photons),
        spp_(s.settings.spp > 0 ? s.settings.spp : kDefaultCameraSamples),
        alpha_(s.settings.alpha),
        radius_(s.settings.radius),
        seed_(s.settings.seed),
        host_gather_(gather_on_host(s.settings.gather)),
        edge_correction_(s.settings.edge_correction),
        photon_floats_(KASHA_PHOTON_FLOATS(s.scene.grid.bins)),
        vp_floats_(KASHA_VP_FLOATS(s.scene.grid.bins, film_.rows(), s.scene.fluorescent())),
        layout_{s.scene.grid.bins, film_.rows(), film_.spectral(), s.scene.fluorescent(),
                film_.cmf().data()} {
    if (photons_ > (1LL << 31) - 1) throw Error("--photons: at most 2^31 - 1 photons per pass");
    if (!(alpha_ > 0 && alpha_ < 1)) throw Error("--alpha must lie in (0, 1)");
    photon_kernel_ = cl::Kernel(program_, "trace_photon_map");
    camera_kernel_ = cl::Kernel(program_, "camera_pass");
    cell_size_kernel_ = cl::Kernel(program_, "grid_cell_size");
    coverage_kernel_ = cl::Kernel(program_, "disc_coverage");
    count_kernel_ = cl::Kernel(program_, "grid_count");
    scan_kernel_ = cl::Kernel(program_, "grid_scan");
    scatter_kernel_ = cl::Kernel(program_, "grid_scatter");
    gather_kernel_ = cl::Kernel(program_, "gather_photons");
    update_kernel_ = cl::Kernel(program_, "sppm_update");
    image_kernel_ = cl::Kernel(program_, "sppm_image");
    const size_t pixels = film_.pixels(), rows = film_.rows();
    counter_ = device_buffer(cl_, sizeof(cl_int), "photon: the store counter");
    raised_ = zeroed(sizeof(cl_int), "photon: the count of raised radii");
    cut_ =
        device_buffer(cl_, photon_items() * sizeof(cl_float),
                      "photon: the depth-guard tallies of --photons " + std::to_string(photons_));
    camera_cut_ = device_buffer(cl_, pixels * sizeof(cl_float),
                                "photon: the camera pass's depth-guard tallies");
    rejected_ = device_buffer(cl_, pixels * sizeof(cl_int), "photon: the camera pass's rejections");
    vps_ = device_buffer(cl_, vp_bytes(), "photon: the visible points of the image");
    // The per-pixel state of the render: direct light's sum (and its compensation), the SPPM
    // radius, count and flux τ, and the pass's gather.
    direct_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the direct light's sums");
    direct_carry_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the direct light's sums");
    radius_buf_ = zeroed(pixels * sizeof(cl_float), "photon: the SPPM radii");
    count_ = zeroed(pixels * sizeof(cl_float), "photon: the SPPM counts");
    tau_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the SPPM flux");
    pass_flux_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the pass's gathered flux");
    pass_found_ = zeroed(pixels * sizeof(cl_int), "photon: the pass's photon counts");
    coverage_ = zeroed(pixels * 2 * sizeof(cl_float), "photon: the gather discs' coverage");
    image_ = device_buffer(cl_, pixels * rows * sizeof(cl_float), "photon: the image");
    // The store holds about four photons per emitted one (what a pass of ordinary albedos stores)
    // within the memory budget; passes that store more are gathered in batches, so memory stays
    // the same however long photon paths get.
    const size_t record = photon_floats_ * sizeof(float) + (host_gather_ ? 0 : kGridBytesPerRecord);
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
    store_ = device_buffer(cl_, capacity_ * photon_floats_ * sizeof(float),
                           "photon: the photon store (--memory, --photons)");
    if (!host_gather_) {
      // About one cell per record: hash collisions stay rare without the table outgrowing them.
      cells_ = 1024;
      while (cells_ < capacity_ && cells_ < (1u << 22)) cells_ *= 2;
      cell_ = device_buffer(cl_, 2 * sizeof(cl_float), "photon: the grid's cell size");
      cell_count_ = device_buffer(cl_, cells_ * sizeof(cl_int), "photon: the grid's cells");
      cell_end_ = device_buffer(cl_, cells_ * sizeof(cl_int), "photon: the grid's cells");
      photon_cell_ = device_buffer(cl_, capacity_ * sizeof(cl_uint), "photon: the grid's photons");
      sorted_ = device_buffer(cl_, capacity_ * sizeof(cl_int), "photon: the grid's photons");
    }
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
  }

  PassResult render_pass(int pass) override {
    const auto t0 = Clock::now();
    const double device0 = device_seconds_;
    const size_t pixels = film_.pixels();
    launch(camera_kernel_, pixels, vps_, direct_, direct_carry_, rejected_, camera_cut_,
           radius_buf_, static_cast<cl_float>(radius_), static_cast<cl_float>(footprint_),
           static_cast<cl_float>(max_radius_), raised_, spp_, seed_, static_cast<cl_uint>(pass));
    PassResult r{pass, spp_, {}, {}, 1.0, {}, {}};
    r.tallies["time: camera pass (s)"] = device_seconds_ - device0;
    warn_raised_radii();
    if (host_gather_) {
      read_floats(vps_, pixels * vp_floats_, vps_host_);
      read_floats(radius_buf_, pixels, radius_host_);
      host_flux_.assign(pixels * film_.rows(), 0.0);
      host_found_.assign(pixels, 0);
    } else {
      launch_range(cell_size_kernel_, 0, work_group_size(cell_size_kernel_), vps_, radius_buf_,
                   static_cast<cl_int>(pixels), cell_);
    }
    const double traced = trace_and_gather(pass, r.tallies);
    if (host_gather_) {
      std::vector<float> flux(host_flux_.begin(), host_flux_.end());
      cl_.queue().enqueueWriteBuffer(pass_flux_, CL_TRUE, 0, flux.size() * sizeof(float),
                                     flux.data());
      cl_.queue().enqueueWriteBuffer(pass_found_, CL_TRUE, 0, pixels * sizeof(cl_int),
                                     host_found_.data());
    }
    // A pass cut short (deadline, Ctrl-C) estimates with the photons it traced: each carries
    // 1/photons of the lights' power, so their flux is scaled up to the pass's photons.
    r.fraction = traced / static_cast<double>(photons_);
    double t = device_seconds_;
    if (edge_correction_) {
      // With the radii this pass gathered within; a fresh rotation of the probes each pass, so
      // their pattern averages out over passes.
      const float rotation =
          static_cast<float>(2 * M_PI * std::fmod(0.6180339887 * pass + 1e-3 * seed_, 1.0));
      launch(coverage_kernel_, pixels, vps_, radius_buf_, coverage_, kCoverageProbes, rotation);
    }
    launch(update_kernel_, pixels, radius_buf_, count_, tau_, pass_flux_, pass_found_,
           static_cast<cl_float>(alpha_), static_cast<cl_float>(1.0 / r.fraction));
    r.tallies["time: SPPM update and edge probes (s)"] = device_seconds_ - t;
    ++passes_;
    r.kept = [this] { return read_image(); };
    r.tallies[kDepthGuardOf] = traced;
    r.tallies[kCameraDepthGuardCut] = read_sum<cl_float>(camera_cut_, pixels);
    r.tallies[kCameraDepthGuardOf] = static_cast<double>(pixels) * spp_;
    r.tallies["rejected samples"] = read_sum<cl_int>(rejected_, pixels);
    add_ray_tallies(r);
    // What the device did not do: everything else in the pass, the host's share.
    r.tallies["time: host (s)"] = since(t0) - (device_seconds_ - device0);
    return r;
  }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels()) * spp_;
  }
  long long photons_per_pass() const override { return photons_; }
  std::map<std::string, size_t> device_buffers() const override {
    const size_t pixels = film_.pixels(), rows = film_.rows(), f = sizeof(float);
    std::map<std::string, size_t> b{{"visible points", vp_bytes()},
                                    {"photon store", capacity_ * photon_floats_ * f},
                                    {"pixel statistics", pixels * (5 * rows + 7) * f}};
    if (!host_gather_) b["photon grid"] = cells_ * 2 * f + capacity_ * kGridBytesPerRecord;
    return b;
  }

 private:
  size_t vp_bytes() const { return film_.pixels() * vp_floats_ * sizeof(float); }
  size_t photon_items() const { return (photons_ + kPhotonsPerItem - 1) / kPhotonsPerItem; }

  cl::Buffer zeroed(size_t bytes, const std::string& what) {
    cl::Buffer b = device_buffer(cl_, bytes, what);
    cl_.queue().enqueueFillBuffer(b, cl_int(0), 0, bytes);
    cl_.queue().finish();
    return b;
  }

  void read_floats(const cl::Buffer& b, size_t count, std::vector<float>& out) {
    out.resize(count);
    cl_.queue().enqueueReadBuffer(b, CL_TRUE, 0, count * sizeof(float), out.data());
  }

  // The image so far: direct light's mean plus the SPPM radiance, per pixel and film row.
  std::vector<float> read_image() {
    launch(image_kernel_, film_.pixels(), direct_, radius_buf_, tau_, coverage_,
           static_cast<cl_int>(edge_correction_), static_cast<cl_float>(passes_), image_);
    std::vector<float> image;
    read_floats(image_, film_.pixels() * film_.rows(), image);
    return image;
  }

  // A radius far below a pixel's footprint catches no photon for many passes (camera_pass).
  void warn_raised_radii() {
    if (radius_ <= 0 || warned_small_) return;
    cl_int raised = 0;
    cl_.queue().enqueueReadBuffer(raised_, CL_TRUE, 0, sizeof(cl_int), &raised);
    if (raised == 0) return;
    warned_small_ = true;
    warn("--radius " + std::to_string(radius_) +
         " is below 1/100 of a pixel's footprint at the visible points; using that");
  }

  // Traces the pass's photons in launches of bounded time into the store, gathering each time
  // the store is full and at the end; stops early on the deadline or Ctrl-C. Returns the
  // photons traced.
  double trace_and_gather(int pass, std::map<std::string, double>& tallies) {
    size_t done = 0, stored = 0;  // photons traced, records in the store
    double per_photon = 4;        // records a photon stores, as measured so far
    double trace_s = 0, gather_s = 0, records = 0, cut = 0;
    gathers_ = 0;
    auto gather_store = [&] {
      double t = device_seconds_;
      gather_batch(stored);
      gather_s += device_seconds_ - t;
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
      const double device_before = device_seconds_;
      cl_int after = launch_photons(pass, done, n, 0, stored);
      trace_s += device_seconds_ - device_before;
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
        cut += trace_long_photon(pass, done, gather_s, records, trace_s);
        ++done;
      }
    }
    if (stored > 0) gather_store();
    tallies["time: photon tracing (s)"] = trace_s;
    tallies["time: grid and gather (s)"] = gather_s;
    tallies["photons stored"] = records;
    tallies[kGatherQueries] = gathers_ * static_cast<double>(film_.pixels());
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
  double trace_long_photon(int pass, size_t index, double& gather_s, double& records,
                           double& trace_s) {
    double cut = 0;
    for (size_t skip = 0;; skip += capacity_) {
      if (skip > (1u << 31) - 1) throw Error("photon: one photon stored more than 2^31 records");
      double t = device_seconds_;
      cl_int after = launch_photons(pass, index, 1, static_cast<int>(skip), 0);
      trace_s += device_seconds_ - t;
      if (skip == 0) cut = read_sum<cl_float>(cut_, 1);
      const size_t batch = std::min<size_t>(static_cast<size_t>(after), capacity_);
      t = device_seconds_;
      gather_batch(batch);
      gather_s += device_seconds_ - t;
      records += static_cast<double>(batch);
      if (static_cast<size_t>(after) <= capacity_) return cut;
      if (interrupt_requested()) return cut;  // the photon's remaining stores are lost; rare
    }
  }

  // Adds the gather of the first `count` stored photons to the pass's (radii fixed in a pass).
  void gather_batch(size_t count) {
    if (count == 0) return;
    ++gathers_;
    if (host_gather_) {
      read_floats(store_, count * photon_floats_, photons_host_);
      PhotonKdTree tree(photons_host_.data(), count, photon_floats_);
      std::vector<double> radius(radius_host_.begin(), radius_host_.end());
      GatherResult found = tree.gather(vps_host_.data(), vp_floats_, film_.pixels(), radius, layout_);
      for (size_t i = 0; i < host_flux_.size(); ++i) host_flux_[i] += found.flux[i];
      for (size_t p = 0; p < host_found_.size(); ++p) host_found_[p] += found.found[p];
      return;
    }
    // The grid by counting sort: photons per cell, each cell's end by a prefix sum, then each
    // photon's place in its cell's run.
    const cl_uint mask = static_cast<cl_uint>(cells_ - 1);
    cl_.queue().enqueueFillBuffer(cell_count_, cl_int(0), 0, cells_ * sizeof(cl_int));
    launch(count_kernel_, count, store_, cell_, mask, cell_count_, photon_cell_);
    launch_range(scan_kernel_, 0, work_group_size(scan_kernel_), cell_count_,
                 static_cast<cl_int>(cells_), cell_end_);
    launch(scatter_kernel_, count, photon_cell_, cell_end_, sorted_);
    launch(gather_kernel_, film_.pixels(), vps_, radius_buf_, store_, sorted_, cell_count_,
           cell_end_, cell_, mask, pass_flux_, pass_found_);
  }

  long long photons_;
  int spp_;
  double alpha_, radius_;
  unsigned seed_;
  bool host_gather_;
  bool edge_correction_;
  int photon_floats_, vp_floats_;
  VertexFactorLayout layout_;
  double footprint_;   // pixel width on the image plane at unit distance
  double max_radius_;  // no gather radius beyond this
  bool warned_small_ = false;
  size_t capacity_;  // photon records the store holds
  size_t cells_ = 0;  // the grid's hash table
  int passes_ = 0;
  int gathers_ = 0;  // gathers of the store in this pass: each queries every visible point
  LaunchPacer pacer_{0.2, 256};  // in photons: the first launch is small, as paths may be long
  std::vector<float> vps_host_, radius_host_, photons_host_;  // --gather host
  std::vector<double> host_flux_;
  std::vector<int> host_found_;
  cl::Kernel photon_kernel_, camera_kernel_, cell_size_kernel_, count_kernel_, scan_kernel_,
      scatter_kernel_, gather_kernel_, update_kernel_, image_kernel_, coverage_kernel_;
  cl::Buffer store_, counter_, raised_, vps_, cut_, camera_cut_, rejected_;
  cl::Buffer coverage_, direct_, direct_carry_, radius_buf_, count_, tau_, pass_flux_, pass_found_, image_;
  cl::Buffer cell_, cell_count_, cell_end_, photon_cell_, sorted_;
};

KASHA_REGISTER_INTEGRATOR(
    PhotonMapIntegrator, "photon",
    "bidirectional photon mapping (SPPM): next-event estimation for direct light, photons for "
    "the rest, gathered at visible points with compact rank-1 factors through a hashed grid on "
    "the device",
    {"--photons", "--alpha", "--radius", "--memory", "--spp", "--gather", "--edge-correction"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false});

}  // namespace kasha
