// `--integrator photon` (the default): bidirectional photon mapping, progressive as stochastic
// progressive photon mapping (Hachisuka & Jensen 2009), the whole pass on the device
// (kernels/photon/photon_map.cl, photon_gather.cl). This file orchestrates a pass: a camera pass —
// `--spp` paths per pixel with next-event estimation for direct light, the first storing the
// pixel's visible point — then the pass's photons in chunks (photon_pass_chunks.h), each traced
// into the photon store (photon_store.h) and gathered at every visible point, each time the
// store is full and at the end, through the hashed grid (photon_grid.h) or, with `--gather host`,
// a k-d tree on the host (photon_host_gather.h); then the per-pixel SPPM statistics are updated
// on the device. Only the image crosses to the host, when it is wanted.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/warning.h"
#include "integrators/photon/photon_grid.h"
#include "integrators/photon/photon_host_gather.h"
#include "integrators/photon/photon_pass_chunks.h"
#include "integrators/photon/photon_store.h"
#include "opencl/device_buffer.h"
#include "render/depth_cap.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "render/merge_radius.h"
#include "render/pass_chunks.h"
#include "render/record_bytes.h"
#include "shared/launch_records.h"

namespace kasha {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

// Photons per pass unless --photons says.
constexpr long long kPhotonMapPhotons = 1 << 18;

// Probes per visible point and pass of the edge correction (disc_coverage in photon_gather.cl):
// few, as their ratio of sums averages over passes.
constexpr int kCoverageProbes = 4;

// Camera samples per pixel per pass unless --spp says: direct light, lamps seen directly and
// their edges converge with them while photon tracing dominates the pass (docs/integrators.md).
constexpr int kDefaultCameraSamples = 8;

class PhotonMapIntegrator : public KernelIntegrator, public ChunkWorker {
 public:
  explicit PhotonMapIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "photon/photon_map.cl"),
        photons_(s.settings.photons > 0 ? s.settings.photons : kPhotonMapPhotons),
        spp_(s.settings.spp > 0 ? s.settings.spp : kDefaultCameraSamples),
        alpha_(s.settings.alpha),
        radius_(s.settings.radius),
        seed_(s.settings.seed),
        edge_correction_(s.settings.edge_correction),
        photon_floats_(KASHA_PHOTON_FLOATS(s.scene.grid.bins, s.scene.scattering())),
        vp_floats_(KASHA_VP_FLOATS(s.scene.grid.bins, film_.rows(), s.scene.fluorescent(), s.scene.scattering())) {
    if (photons_ > (1LL << 31) - 1) throw Error("--photons: at most 2^31 - 1 photons per pass");
    if (!(alpha_ > 0 && alpha_ < 1)) throw Error("--alpha must lie in (0, 1)");
    camera_kernel_ = cl::Kernel(program_, "camera_pass");
    coverage_kernel_ = cl::Kernel(program_, "disc_coverage");
    update_kernel_ = cl::Kernel(program_, "sppm_update");
    image_kernel_ = cl::Kernel(program_, "sppm_image");
    allocate_pixel_state();
    // `--gather auto` is the device on every device type (measured on PoCL's CPU device too:
    // docs/integrators.md).
    const bool host_gather = s.settings.gather == Gather::host;
    KernelLauncher& device = *this;  // the store and the grid launch their kernels through it
    const size_t record = photon_floats_ * sizeof(float) + (host_gather ? 0 : kGridBytesPerRecord);
    store_ = std::make_unique<PhotonStore>(device, program_, photons_, seed_, photon_floats_,
                                           record, chunk_photons(static_cast<size_t>(photons_)),
                                           s.settings.memory);
    if (host_gather)
      host_gather_.emplace(photon_floats_, vp_floats_, film_.pixels(),
                           VertexFactorLayout{s.scene.grid.bins, film_.rows(), film_.spectral(),
                                              s.scene.fluorescent(), film_.cmf().data()},
                           depth_cap(s.settings, s.scene));
    else
      grid_ = std::make_unique<PhotonGrid>(device, program_, store_->capacity());
    set_radius_bounds(s.scene);
  }

  PassResult render_pass(int pass) override {
    const auto t0 = Clock::now();
    const double device0 = device_seconds_;
    const size_t pixels = film_.pixels();
    const KPhotonCameraLaunch record{static_cast<float>(radius_),
                                     static_cast<float>(footprint_),
                                     static_cast<float>(max_radius_),
                                     spp_,
                                     seed_,
                                     static_cast<uint>(pass)};
    launch(camera_kernel_, pixels, vps_, direct_, direct_carry_, rejected_, camera_cut_,
           radius_buf_, raised_, record);
    PassResult r{pass, spp_, {}, {}, 1.0, {}, {}};
    r.counters.add_stage("camera pass", device_seconds_ - device0);
    warn_raised_radii();
    if (grid_) grid_->size_cells(vps_, radius_buf_, pixels);
    const ChunkResult gathered = gather_pass(pass);
    const std::vector<float> flux(gathered.flux.begin(), gathered.flux.end());
    cl_.queue().enqueueWriteBuffer(pass_flux_, CL_TRUE, 0, flux.size() * sizeof(float),
                                   flux.data());
    cl_.queue().enqueueWriteBuffer(pass_found_, CL_TRUE, 0, pixels * sizeof(cl_int),
                                   gathered.found.data());
    // A pass cut short (deadline, Ctrl-C) estimates with the photons it traced: each carries
    // 1/photons of the lights' power, so their flux is scaled up to the pass's photons.
    r.fraction = gathered.traced / static_cast<double>(photons_);
    update_statistics(pass, r);
    ++passes_;
    r.kept = [this] { return read_image(); };
    add_pass_counters(gathered, r);
    r.counters.add_stage("host", std::max(0.0, seconds_since(t0) - (device_seconds_ - device0)));
    return r;
  }

  // Several devices: the others' instances (or their proxies on other MPI ranks) trace and
  // gather chunks of each pass's photons.
  ChunkWorker* chunk_worker() override { return this; }
  void set_helpers(const std::vector<ChunkWorker*>& helpers) override { helpers_ = helpers; }

  size_t chunk_capacity() const override { return store_->capacity(); }
  void set_chunk_control(const PassControl& control) override { set_control(control); }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels()) * spp_;
  }
  long long photons_per_pass() const override { return photons_; }
  std::map<std::string, size_t> device_buffers() const override {
    const size_t pixels = film_.pixels(), rows = film_.rows(), f = sizeof(float);
    std::map<std::string, size_t> b{{"visible points", vp_bytes()},
                                    {"photon store", store_->bytes()},
                                    {"pixel statistics", pixels * (5 * rows + 7) * f}};
    if (grid_) b["photon grid"] = grid_->bytes(store_->capacity());
    return b;
  }

 private:
  size_t vp_bytes() const { return film_.pixels() * vp_floats_ * sizeof(float); }

  cl::Buffer zeroed(size_t bytes, const std::string& what) {
    cl::Buffer b = device_buffer(cl_, bytes, what);
    cl_.queue().enqueueFillBuffer(b, cl_int(0), 0, bytes);
    cl_.queue().finish();
    return b;
  }

  // The per-pixel state of the render: the visible points, direct light's sum (and its
  // compensation), the SPPM radius, count and flux τ, the pass's gather, the edge probes' sums.
  void allocate_pixel_state() {
    const size_t pixels = film_.pixels(), rows = film_.rows();
    raised_ = zeroed(sizeof(cl_int), "photon: the count of raised radii");
    camera_cut_ = device_buffer(cl_, pixels * sizeof(cl_float),
                                "photon: the camera pass's depth-guard tallies");
    rejected_ = device_buffer(cl_, pixels * sizeof(cl_int), "photon: the camera pass's rejections");
    vps_ = device_buffer(cl_, vp_bytes(), "photon: the visible points of the image");
    direct_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the direct light's sums");
    direct_carry_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the direct light's sums");
    radius_buf_ = zeroed(pixels * sizeof(cl_float), "photon: the SPPM radii");
    count_ = zeroed(pixels * sizeof(cl_float), "photon: the SPPM counts");
    tau_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the SPPM flux");
    pass_flux_ = zeroed(pixels * rows * sizeof(cl_float), "photon: the pass's gathered flux");
    pass_found_ = zeroed(pixels * sizeof(cl_int), "photon: the pass's photon counts");
    coverage_ = zeroed(pixels * 2 * sizeof(cl_float), "photon: the gather discs' coverage");
    image_ = device_buffer(cl_, pixels * rows * sizeof(cl_float), "photon: the image");
  }

  // The pixel footprint that sets the first radii, and the largest radius (render/merge_radius.h).
  void set_radius_bounds(const Scene& scene) {
    const MergeRadiusBounds bounds = merge_radius_bounds(scene, scene_.data().camera);
    footprint_ = bounds.footprint;
    max_radius_ = bounds.largest;
    if (radius_ > max_radius_) warn_radius_beyond(radius_, bounds);
  }

  // The SPPM statistics after the pass's gathers, with the edge probes first.
  void update_statistics(int pass, PassResult& r) {
    const size_t pixels = film_.pixels();
    double t = device_seconds_;
    if (edge_correction_) {
      // With the radii this pass gathered within; a fresh rotation of the probes each pass, so
      // their pattern averages out over passes.
      const float rotation =
          static_cast<float>(2 * M_PI * std::fmod(0.6180339887 * pass + 1e-3 * seed_, 1.0));
      launch(coverage_kernel_, pixels, vps_, radius_buf_, coverage_, kCoverageProbes, rotation);
    }
    launch_own(update_kernel_, pixels, radius_buf_, count_, tau_, pass_flux_, pass_found_,
               static_cast<cl_float>(alpha_), static_cast<cl_float>(1.0 / r.fraction));
    r.counters.add_stage("SPPM update and edge probes", device_seconds_ - t);
  }

  // Stage times add over the devices; with several, "host" is what this device's thread spent
  // beyond its own launches (waiting for the others included).
  void add_pass_counters(const ChunkResult& gathered, PassResult& r) {
    const size_t pixels = film_.pixels();
    PassCounters& c = r.counters;
    c.add_stage("photon tracing", gathered.trace_s);
    c.add_stage("grid and gather", gathered.gather_s);
    c.photons_stored = gathered.records;
    c.photon_store_overflows = gathered.overflows;
    c.gather_queries = gathered.gathers * static_cast<double>(pixels);
    // The chunks' rays (on whichever device), then this device's camera pass and probes.
    c.closest_rays = gathered.closest_rays;
    c.shadow_rays = gathered.shadow_rays;
    add_ray_counts(r);
    c.depth_guard = {gathered.cut, gathered.traced};  // per photon's start
    c.camera_depth_guard = {read_sum<cl_float>(camera_cut_, pixels),
                            static_cast<double>(pixels) * spp_};
    c.rejected_samples = read_sum<cl_int>(rejected_, pixels);
    c.device_work = gathered.work;
  }

  // The image so far: direct light's mean plus the SPPM radiance, per pixel and film row.
  std::vector<float> read_image() {
    launch_own(image_kernel_, film_.pixels(), scene_.data().bin_nm, direct_, radius_buf_, tau_,
               coverage_, static_cast<cl_int>(edge_correction_), static_cast<cl_float>(passes_),
               image_);
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

  // The pass's photons in chunks on this device and the helpers (photon_pass_chunks.h), with
  // the camera pass's visible points, radii and cell size copied to whoever needs them.
  ChunkResult gather_pass(int pass) {
    const size_t pixels = film_.pixels(), photons = static_cast<size_t>(photons_);
    PassInputs inputs;
    if (host_gather_ || !helpers_.empty()) {
      read_floats(vps_, pixels * vp_floats_, inputs.visible_points);
      read_floats(radius_buf_, pixels, inputs.radius);
      if (grid_) read_floats(grid_->cell(), 2, inputs.cell);
    }
    if (host_gather_) host_gather_->take_inputs(inputs);
    size_t capacity = store_->capacity();
    for (const ChunkWorker* h : helpers_) capacity = std::min(capacity, h->chunk_capacity());
    std::vector<ChunkWorker*> workers{this};
    workers.insert(workers.end(), helpers_.begin(), helpers_.end());
    ChunkResult total =
        share_pass(pass, photons, fitting_chunk_photons(photons, capacity, per_photon_), workers,
                   inputs, control_, pixels * film_.rows(), pixels);
    if (total.traced == static_cast<double>(photons))
      per_photon_ = std::max(per_photon_, total.per_photon);  // for the next pass's chunks
    return total;
  }

  // A helper's copy of the main device's visible points, radii and cell size for this pass.
  void take_inputs(const PassInputs& in) override {
    if (host_gather_) {
      host_gather_->take_inputs(in);
      return;
    }
    cl_.queue().enqueueWriteBuffer(vps_, CL_FALSE, 0, in.visible_points.size() * sizeof(float),
                                   in.visible_points.data());
    cl_.queue().enqueueWriteBuffer(radius_buf_, CL_FALSE, 0, in.radius.size() * sizeof(float),
                                   in.radius.data());
    cl_.queue().enqueueWriteBuffer(grid_->cell(), CL_TRUE, 0, in.cell.size() * sizeof(float),
                                   in.cell.data());
  }

  // Traces and gathers photons [first, first + count) on this device; `progress` counts the
  // photons traced on every device (the main one shows it).
  ChunkResult trace_chunk(int pass, size_t first, size_t count,
                          std::atomic<size_t>& progress) override {
    const size_t pixels = film_.pixels(), rows = film_.rows();
    ChunkResult c;
    if (host_gather_) {
      c.flux.assign(pixels * rows, 0.0);
      c.found.assign(pixels, 0);
    } else {  // the device's pass buffers hold the chunk's gather
      cl_.queue().enqueueFillBuffer(pass_flux_, cl_float(0), 0, pixels * rows * sizeof(float));
      cl_.queue().enqueueFillBuffer(pass_found_, cl_int(0), 0, pixels * sizeof(cl_int));
    }
    store_->trace(
        pass, first, count, control_, progress,
        [this](size_t records, ChunkResult& r) { gather_store(records, r); }, c);
    const DeviceFilm::RayCounts rays = film_.take_ray_counts();
    c.closest_rays = static_cast<double>(rays.closest);
    c.shadow_rays = static_cast<double>(rays.shadow);
    if (!host_gather_) {
      std::vector<float> flux;
      read_floats(pass_flux_, pixels * rows, flux);
      c.flux.assign(flux.begin(), flux.end());
      c.found.resize(pixels);
      cl_.queue().enqueueReadBuffer(pass_found_, CL_TRUE, 0, pixels * sizeof(cl_int),
                                    c.found.data());
    }
    return c;
  }

  // Adds the gather of the store's first `count` records to the chunk's (radii fixed in a pass).
  void gather_store(size_t count, ChunkResult& c) {
    const double t = device_seconds_;
    const auto start = Clock::now();
    c.records += static_cast<double>(count);
    c.gathers += 1;
    if (host_gather_) {
      read_floats(store_->records(), count * photon_floats_, records_host_);
      host_gather_->gather(records_host_, count, c);
      c.gather_s += seconds_since(start);
      return;
    }
    grid_->gather(store_->records(), count, vps_, radius_buf_, pass_flux_, pass_found_);
    c.gather_s += device_seconds_ - t;
  }

  long long photons_;
  int spp_;
  double alpha_, radius_;
  unsigned seed_;
  bool edge_correction_;
  int photon_floats_, vp_floats_;
  double footprint_;   // pixel width on the image plane at unit distance
  double max_radius_;  // no gather radius beyond this
  bool warned_small_ = false;
  int passes_ = 0;
  double per_photon_ =
      4;  // records per photon, as measured: the store holds ~4 for ordinary albedos
  std::vector<ChunkWorker*> helpers_;  // the other devices' instances, or remote proxies
  std::unique_ptr<PhotonStore> store_;
  std::unique_ptr<PhotonGrid> grid_;       // the device's gather
  std::optional<HostGather> host_gather_;  // --gather host
  std::vector<float> records_host_;        // --gather host: a store read back
  cl::Kernel camera_kernel_, update_kernel_, image_kernel_, coverage_kernel_;
  cl::Buffer raised_, vps_, camera_cut_, rejected_;
  cl::Buffer coverage_, direct_, direct_carry_, radius_buf_, count_, tau_, pass_flux_, pass_found_,
      image_;
};

KASHA_REGISTER_INTEGRATOR(
    PhotonMapIntegrator, "photon",
    "bidirectional photon mapping (SPPM): next-event estimation for direct light, photons for "
    "the rest, gathered at visible points with compact rank-1 factors through a hashed grid on "
    "the device",
    {{"--photons", IntegratorOption::Value::integer, 1, 2147483647, "photons per pass",
      number_text(kPhotonMapPhotons), KASHA_SETTING(photons)},
     {"--alpha", IntegratorOption::Value::number, 0.01, 0.99, "SPPM's radius reduction α",
      number_text(IntegratorSettings::kDefaultAlpha), KASHA_SETTING(alpha)},
     {"--radius", IntegratorOption::Value::positive, 0, 1e300, "initial gather radius",
      "from the pixel footprint", KASHA_SETTING(radius)},
     {"--memory", IntegratorOption::Value::bytes, 1, 1125899906842624.0 /* 2^50 */,
      "memory for the photon store, bytes with an optional unit (512MiB, 2GB)",
      "a quarter of the device's memory, an eighth on a CPU", KASHA_SETTING(memory),
      /*device's own*/ true},
     {"--spp", IntegratorOption::Value::integer, 1, 1 << 20, "camera samples per pixel per pass",
      std::to_string(kDefaultCameraSamples), KASHA_SETTING(spp)},
     {"--gather", IntegratorOption::Value::choice, 0, 0,
      "gather on the device (a hashed grid) or on the host (nanoflann)", "auto: the device",
      KASHA_SETTING(gather)},
     {"--edge-correction", IntegratorOption::Value::flag, 0, 0,
      "divide the density by the measured fraction of the gather discs on accepted surface "
      "(--edge-correction=false leaves it out)",
      "on", KASHA_SETTING(edge_correction)}},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ false,
                     /*samples seen light*/ false, /*medium light paths*/ true});

}  // namespace kasha
