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
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "integrators/photon/photon_chunks.h"
#include "integrators/photon/photon_gather.h"
#include "integrators/photon/photon_records.h"
#include "opencl/device_buffer.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"

namespace kasha {

namespace {
constexpr int kPhotonsPerItem = 64;
// A pass's photons go in about this many chunks, of at least kChunkPhotons each: enough to share
// a pass among a few devices, few enough that the gathers' per-pixel work stays small.
constexpr size_t kChunksPerPass = 8;
constexpr size_t kChunkPhotons = 1 << 15;
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

class PhotonMapIntegrator : public KernelIntegrator, public ChunkWorker {
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
    sort_kernel_ = cl::Kernel(program_, "grid_sort_cells");
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
    // The store holds a chunk of a pass's photons (chunk_photons) at about four records each
    // (what ordinary albedos store) with a margin, within the memory budget; chunks that store
    // more are traced in smaller pieces, so memory stays the same however long photon paths get.
    const size_t record = photon_floats_ * sizeof(float) + (host_gather_ ? 0 : kGridBytesPerRecord);
    const size_t budget = s.settings.memory > 0 ? static_cast<size_t>(s.settings.memory)
                                                : default_memory_budget(cl_.info());
    // At least 2^18 records, so a pass of few photons with long paths fills the store in
    // launches of many photons rather than one photon at a time.
    capacity_ = std::min<size_t>(
        {std::max<size_t>(base_chunk_photons() * 5 + 1024, 1u << 18), budget / record,
         (1u << 31) - 1});
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
    if (!host_gather_)
      launch_own_range(cell_size_kernel_, 0, work_group_size(cell_size_kernel_), vps_, radius_buf_,
                       static_cast<cl_int>(pixels), cell_);
    PassInputs inputs;
    if (host_gather_ || !helpers_.empty()) {
      read_floats(vps_, pixels * vp_floats_, inputs.visible_points);
      read_floats(radius_buf_, pixels, inputs.radius);
      if (!host_gather_) read_floats(cell_, 2, inputs.cell);
    }
    const ChunkResult gathered = gather_pass(pass, inputs);
    const std::vector<float> flux(gathered.flux.begin(), gathered.flux.end());
    cl_.queue().enqueueWriteBuffer(pass_flux_, CL_TRUE, 0, flux.size() * sizeof(float),
                                   flux.data());
    cl_.queue().enqueueWriteBuffer(pass_found_, CL_TRUE, 0, pixels * sizeof(cl_int),
                                   gathered.found.data());
    // A pass cut short (deadline, Ctrl-C) estimates with the photons it traced: each carries
    // 1/photons of the lights' power, so their flux is scaled up to the pass's photons.
    r.fraction = gathered.traced / static_cast<double>(photons_);
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
    r.tallies["time: SPPM update and edge probes (s)"] = device_seconds_ - t;
    ++passes_;
    r.kept = [this] { return read_image(); };
    // Stage times add over the devices; with several, "host" is what this device's thread spent
    // beyond its own launches (waiting for the others included).
    r.tallies["time: photon tracing (s)"] = gathered.trace_s;
    r.tallies["time: grid and gather (s)"] = gathered.gather_s;
    r.tallies["photons stored"] = gathered.records;
    r.tallies["photon store overflows"] = gathered.overflows;
    r.tallies[kGatherQueries] = gathered.gathers * static_cast<double>(pixels);
    // The chunks' rays (on whichever device), then this device's camera pass and probes.
    r.tallies[kClosestRays] = gathered.closest_rays;
    r.tallies[kShadowRays] = gathered.shadow_rays;
    add_ray_tallies(r);
    r.tallies[kDepthGuardCut] = gathered.cut;  // per photon's start
    r.tallies[kDepthGuardOf] = gathered.traced;
    r.tallies[kCameraDepthGuardCut] = read_sum<cl_float>(camera_cut_, pixels);
    r.tallies[kCameraDepthGuardOf] = static_cast<double>(pixels) * spp_;
    r.tallies["rejected samples"] = read_sum<cl_int>(rejected_, pixels);
    r.tallies["time: host (s)"] = std::max(0.0, since(t0) - (device_seconds_ - device0));
    for (const auto& [name, photons] : gathered.work) r.tallies[name] = photons;
    return r;
  }

  bool independent_passes() const override { return false; }

  // Several devices: the others' instances (or their proxies on other MPI ranks) trace and
  // gather chunks of each pass's photons.
  void set_helpers(const std::vector<Integrator*>& helpers) override {
    helpers_.clear();
    for (Integrator* h : helpers) {
      auto* p = dynamic_cast<ChunkWorker*>(h);
      if (!p) throw Error("photon: a helper device runs another integrator");
      helpers_.push_back(p);
    }
  }

  size_t chunk_capacity() const override { return capacity_; }
  void set_chunk_control(const PassControl& control) override { set_control(control); }

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

  // Photons per chunk: a pass's photons are traced and gathered in chunks of fixed photon ranges,
  // whichever device takes each, and the chunks' gathers add up in chunk order — so one device
  // or several give the same image, bit for bit. A chunk's records fit the smallest store with a
  // margin, as far as measured (a chunk that overflows is traced again in halves).
  size_t chunk_photons() const {
    size_t capacity = capacity_;
    for (const ChunkWorker* h : helpers_) capacity = std::min(capacity, h->chunk_capacity());
    const size_t fit = static_cast<size_t>(static_cast<double>(capacity) / (per_photon_ * 1.25));
    return std::clamp<size_t>(fit, 1, base_chunk_photons());
  }
  size_t base_chunk_photons() const {
    const size_t photons = static_cast<size_t>(photons_);
    return std::min(photons, std::max(kChunkPhotons, (photons + kChunksPerPass - 1) / kChunksPerPass));
  }

  // The pass's photons, chunk by chunk on this device and the helpers (a thread each), handed
  // out in order as devices come free; the chunks' gathers add up on the host in chunk order.
  ChunkResult gather_pass(int pass, const PassInputs& inputs) {
    const size_t photons = static_cast<size_t>(photons_), chunk = chunk_photons();
    const size_t chunks = (photons + chunk - 1) / chunk;
    ChunkResult total;
    total.flux.assign(film_.pixels() * film_.rows(), 0.0);
    total.found.assign(film_.pixels(), 0);
    std::vector<std::optional<ChunkResult>> results(chunks);
    size_t added = 0;
    std::mutex mutex;
    std::condition_variable ready;
    std::exception_ptr failure;
    std::atomic<size_t> next{0}, progress{0};
    // Adds the chunks that are ready, in order; called with the lock held.
    auto add_ready = [&] {
      for (; added < chunks && results[added]; ++added) {
        ChunkResult& c = *results[added];
        for (size_t i = 0; i < c.flux.size(); ++i) total.flux[i] += c.flux[i];
        for (size_t p = 0; p < c.found.size(); ++p) total.found[p] += c.found[p];
        total.traced += c.traced;
        total.records += c.records;
        total.cut += c.cut;
        total.overflows += c.overflows;
        total.gathers += c.gathers;
        total.closest_rays += c.closest_rays;
        total.shadow_rays += c.shadow_rays;
        total.trace_s += c.trace_s;
        total.gather_s += c.gather_s;
        total.per_photon = std::max(total.per_photon, c.per_photon);
        c = ChunkResult{};
      }
    };
    std::vector<double> work_done(helpers_.size() + 1, 0.0);
    // Every worker's deadline is this pass's (its control's), so it is checked here for all.
    auto work = [&](ChunkWorker& lane, size_t index) {
      for (size_t c; (c = next++) < chunks;) {
        const size_t first = c * chunk;
        ChunkResult result;
        if (c == 0 || !control_.stop_now())
          result = lane.trace_chunk(pass, first, std::min(chunk, photons - first), progress);
        std::lock_guard<std::mutex> lock(mutex);
        work_done[index] += result.traced;
        results[c] = std::move(result);
        add_ready();
        ready.notify_all();
      }
    };
    std::vector<std::thread> threads;
    PassControl quiet = control_;
    quiet.progress = nullptr;  // progress is this thread's to show
    for (size_t i = 0; i < helpers_.size(); ++i)
      threads.emplace_back([&, i] {
        ChunkWorker* h = helpers_[i];
        try {
          h->set_chunk_control(quiet);
          h->take_inputs(inputs);
          work(*h, i + 1);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex);
          if (!failure) failure = std::current_exception();
          next = chunks;  // no more chunks start; the ones in flight finish
          ready.notify_all();
        }
      });
    try {
      if (host_gather_) take_inputs(inputs);
      work(*this, 0);
      std::unique_lock<std::mutex> lock(mutex);
      ready.wait(lock, [&] { return added == chunks || failure; });
    } catch (...) {
      next = chunks;
      for (std::thread& t : threads) t.join();
      throw;
    }
    for (std::thread& t : threads) t.join();
    if (failure) std::rethrow_exception(failure);
    if (!helpers_.empty())
      for (size_t i = 0; i < work_done.size(); ++i) total.work[device_work_tally(i)] = work_done[i];
    if (total.traced == static_cast<double>(photons))
      per_photon_ = std::max(per_photon_, total.per_photon);  // for the next pass's chunks
    return total;
  }

  // A helper's copy of the main device's visible points, radii and cell size for this pass.
  void take_inputs(const PassInputs& in) override {
    if (host_gather_) {
      vps_host_ = in.visible_points;
      radius_host_ = in.radius;
      return;
    }
    cl_.queue().enqueueWriteBuffer(vps_, CL_FALSE, 0, in.visible_points.size() * sizeof(float),
                                   in.visible_points.data());
    cl_.queue().enqueueWriteBuffer(radius_buf_, CL_FALSE, 0, in.radius.size() * sizeof(float),
                                   in.radius.data());
    cl_.queue().enqueueWriteBuffer(cell_, CL_TRUE, 0, in.cell.size() * sizeof(float),
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
    trace_range(pass, first, count, c, progress);
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

  // Photons [first, first + count) into the empty store in launches of bounded time, then
  // gathered; stops early on the deadline or Ctrl-C. When they overflow the store the range is
  // traced again as two halves — a split that depends on the store's size only.
  void trace_range(int pass, size_t first, size_t count, ChunkResult& c,
                   std::atomic<size_t>& progress) {
    size_t done = 0, stored = 0;
    double cut = 0, trace_s = 0;
    while (done < count) {
      if ((done > 0 || first > 0) && control_.stop_now()) break;
      const size_t n = pacer_.next(count - done);
      auto t = Clock::now();
      const double device_before = device_seconds_;
      cl_int after = launch_photons(pass, first + done, n, 0, stored);
      trace_s += device_seconds_ - device_before;
      if (static_cast<size_t>(after) > capacity_) {
        c.trace_s += trace_s;
        progress -= done;
        if (count == 1) {
          trace_long_photon(pass, first, c);
          progress += 1;
        } else {
          c.per_photon = std::max(c.per_photon, static_cast<double>(capacity_) / count);
          c.overflows += 1;
          trace_range(pass, first, count / 2, c, progress);
          trace_range(pass, first + count / 2, count - count / 2, c, progress);
        }
        return;
      }
      pacer_.record(n, since(t));
      cut += read_sum<cl_float>(cut_, (n + kPhotonsPerItem - 1) / kPhotonsPerItem);
      stored = after;
      done += n;
      progress += n;
      control_.report(static_cast<double>(progress) / photons_);
    }
    gather_batch(stored, c);
    c.trace_s += trace_s;
    c.traced += static_cast<double>(done);
    c.cut += cut;
    if (done == count && done > 0)
      c.per_photon = std::max(c.per_photon, static_cast<double>(stored) / done);
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
  // is the same each time: its random numbers come from its index).
  void trace_long_photon(int pass, size_t index, ChunkResult& c) {
    for (size_t skip = 0;; skip += capacity_) {
      if (skip > (1u << 31) - 1) throw Error("photon: one photon stored more than 2^31 records");
      double t = device_seconds_;
      cl_int after = launch_photons(pass, index, 1, static_cast<int>(skip), 0);
      c.trace_s += device_seconds_ - t;
      if (skip == 0) c.cut += read_sum<cl_float>(cut_, 1);
      gather_batch(std::min<size_t>(static_cast<size_t>(after), capacity_), c);
      if (static_cast<size_t>(after) <= capacity_ || interrupt_requested()) break;
    }
    c.traced += 1;  // a photon cut short by Ctrl-C loses its remaining stores; rare
  }

  // Adds the gather of the first `count` stored photons to the chunk's (radii fixed in a pass).
  void gather_batch(size_t count, ChunkResult& c) {
    if (count == 0) return;
    const double t = device_seconds_;
    const auto start = Clock::now();
    c.records += static_cast<double>(count);
    c.gathers += 1;
    if (host_gather_) {
      read_floats(store_, count * photon_floats_, photons_host_);
      sort_by_key(photons_host_, count);
      PhotonKdTree tree(photons_host_.data(), count, photon_floats_);
      std::vector<double> radius(radius_host_.begin(), radius_host_.end());
      GatherResult found = tree.gather(vps_host_.data(), vp_floats_, film_.pixels(), radius, layout_);
      for (size_t i = 0; i < c.flux.size(); ++i) c.flux[i] += found.flux[i];
      for (size_t p = 0; p < c.found.size(); ++p) c.found[p] += found.found[p];
      c.gather_s += since(start);
      return;
    }
    // The grid by counting sort: photons per cell, each cell's end by a prefix sum, then each
    // photon's place in its cell's run, and each run in key order.
    const cl_uint mask = static_cast<cl_uint>(cells_ - 1);
    cl_.queue().enqueueFillBuffer(cell_count_, cl_int(0), 0, cells_ * sizeof(cl_int));
    launch_own(count_kernel_, count, store_, cell_, mask, cell_count_, photon_cell_);
    launch_own_range(scan_kernel_, 0, work_group_size(scan_kernel_), cell_count_,
                     static_cast<cl_int>(cells_), cell_end_);
    launch_own(scatter_kernel_, count, photon_cell_, cell_end_, sorted_);
    launch_own(sort_kernel_, cells_, store_, cell_count_, cell_end_, sorted_);
    launch_own(gather_kernel_, film_.pixels(), film_.cmf_buffer(), vps_, radius_buf_, store_,
               sorted_, cell_count_, cell_end_, cell_, mask, pass_flux_, pass_found_);
    c.gather_s += device_seconds_ - t;
  }

  // The host's gather takes the records in key order, as the device's does within each cell.
  void sort_by_key(std::vector<float>& records, size_t count) const {
    auto key = [&](size_t i) {
      const float* r = &records[i * photon_floats_];
      uint32_t index, depth;
      std::memcpy(&index, r + KASHA_PHOTON_INDEX, sizeof index);
      std::memcpy(&depth, r + KASHA_PHOTON_DEPTH, sizeof depth);
      return static_cast<uint64_t>(index) << 32 | depth;
    };
    std::vector<size_t> order(count);
    for (size_t i = 0; i < count; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
    std::vector<float> sorted(count * photon_floats_);
    for (size_t i = 0; i < count; ++i)
      std::memcpy(&sorted[i * photon_floats_], &records[order[i] * photon_floats_],
                  photon_floats_ * sizeof(float));
    records.swap(sorted);
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
  double per_photon_ = 4;  // records per photon, as measured: the store holds ~4 for ordinary albedos
  std::vector<ChunkWorker*> helpers_;  // the other devices' instances, or remote proxies
  LaunchPacer pacer_{0.2, 256};  // in photons: the first launch is small, as paths may be long
  std::vector<float> vps_host_, radius_host_, photons_host_;  // --gather host
  cl::Kernel photon_kernel_, camera_kernel_, cell_size_kernel_, count_kernel_, scan_kernel_,
      scatter_kernel_, sort_kernel_, gather_kernel_, update_kernel_, image_kernel_, coverage_kernel_;
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
