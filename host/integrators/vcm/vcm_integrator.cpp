// `--integrator vcm`, `bpt` and `ppm`: vertex connection and merging (kernels/vcm/; Georgiev
// et al. 2012, SmallVCM's vertexcm.hxx) and the two modes that share its kernels — connections
// only (bidirectional path tracing) and merges only (progressive photon mapping, unweighted) —
// each built with only the code it uses. An iteration is a light pass (a light subpath per
// pixel, its vertices stored and splatted to the camera), the hashed grid over the stored
// vertices (render/hash_grid.h), and a camera pass (one path per pixel). The merging radius
// follows a global schedule r_i = r_1 · i^((α−1)/2), so an iteration depends on nothing but its
// index and the seed: iterations are passes the ordered scheduler hands to any device or MPI rank,
// and the image is the same bit for bit however they are shared (docs/integrators.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "integrators/vcm/vcm_plan.h"
#include "opencl/device_buffer.h"
#include "render/fixed_point_film.h"
#include "render/hash_grid.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "render/merge_radius.h"
#include "shared/vcm_records.h"

namespace kasha {

namespace {

// The merges' share of the MIS weights: η = κ π r² L / spp. Georgiev's η counts a merge as L π r²
// independent samples of the path's density, but a merge's photons are shared by the camera paths
// around it and its estimate is a count of a few photons in a disc, so at a diffuse vertex it is
// noisier than that count says and takes weight from connections that do better (Jendersie and
// Grosch 2018 model this fully). κ < 1 weighs merges down where connections also reach the path;
// where no connection does (caustics) a merge keeps the whole weight whatever κ. Both subpaths use
// the same η, so the weights still sum to one. Measured (vcm, RMSE at equal iterations against κ =
// 1): light booth −20 %, Cornell boxes −3 to −4 %, fluorescent furnace −10 %, mirror caustic +3 %,
// glass caustic +0.5 %; κ = 1/16 took the light booth to −24 % but the mirror caustic to +43 %.
constexpr double kMergeWeight = 0.25;

// Samples per camera path of the light seen through delta bounces alone (a lamp, its image in
// glass, a mirror or a coat; kernels/vcm/vcm_seen_light.h), in the pixels where it has an edge
// (seen_light.h). Its MIS weight is 1, so any number is unbiased; each costs a ray or a few, a
// camera path tens. Measured (vcm, RMSE after 20 s against none): the lacquered vase's highlight
// −54 %, the glass of water −51 %, the glass caustic −46 %, a million triangles −17 %, the Cornell
// box −7 %; 16 gained 0–6 % more on those, none elsewhere (docs/integrators.md).
constexpr int kSeenLightSamples = 8;

// Probes of a merge's disc for the edge correction (kernels/transport/disc_coverage.h), once a
// merge has met a photon; each is a short ray through the gather's slab.
constexpr int kCoverageProbes = 8;

KernelDefines mode_defines(VcmMode m, const IntegratorSetup& setup, Merges merges) {
  const IntegratorSettings& s = setup.settings;
  const IntegratorTestHooks& h = setup.hooks;
  KernelDefines d{{"KASHA_VCM_CONNECT", m == VcmMode::ppm ? "0" : "1"},
                  {"KASHA_VCM_MERGE", m == VcmMode::bpt ? "0" : "1"}};
  if (m == VcmMode::vcm && merges == Merges::every) d["KASHA_VCM_MERGE_EVERY"] = "1";
  if (m == VcmMode::vcm && merges == Merges::caustic) d["KASHA_VCM_MERGE_CAUSTIC"] = "1";
  if (m != VcmMode::bpt && s.edge_correction) {
    d["KASHA_VCM_EDGE_CORRECTION"] = "1";
    d["KASHA_VCM_COVERAGE_PROBES"] = std::to_string(kCoverageProbes);
  }
  // The test hooks (kernels/vcm/vcm_modes.h), only when set.
  if (h.vcm_length > 0) d["KASHA_VCM_LENGTH"] = std::to_string(h.vcm_length);
  if (h.vcm_emission_only) d["KASHA_VCM_EMISSION_ONLY"] = "1";
  if (h.vcm_drop_density) d["KASHA_VCM_DROP_DENSITY"] = "1";
  return d;
}

}  // namespace

template <VcmMode Mode>
class VcmIntegrator : public KernelIntegrator {
 public:
  explicit VcmIntegrator(const IntegratorSetup& s) : VcmIntegrator(s, plan_for(Mode, s)) {}

 private:
  VcmIntegrator(const IntegratorSetup& s, const VcmPlan& plan)
      : KernelIntegrator(s, "vcm/vcm.cl", mode_defines(Mode, s, plan.merges)),
        alpha_(s.settings.alpha),
        seed_(s.settings.seed),
        spp_(s.settings.spp > 0 ? s.settings.spp
                                : default_camera_paths(Mode, s.scene, plan.caustic_lit)),
        emission_only_(s.hooks.vcm_emission_only),
        record_floats_(KASHA_VCM_VERTEX_FLOATS(s.scene.grid.bins)),
        light_kernel_(program_, "vcm_light_pass"),
        camera_kernel_(program_, "vcm_camera_pass") {
    if (!(alpha_ > 0 && alpha_ < 1)) throw Error("--alpha must lie in (0, 1)");
    budget_ = s.settings.memory > 0 ? static_cast<size_t>(s.settings.memory)
                                    : default_memory_budget(cl_.info());
    paths_ = s.settings.photons > 0 ? static_cast<size_t>(s.settings.photons)
                                    : default_light_paths(Mode, film_.pixels(), plan.caustic_lit,
                                                          s.scene.scattering());
    set_first_radius(
        s.scene, Mode != VcmMode::bpt ? plan.merging.distance : 0, s.settings.radius,
        Mode != VcmMode::bpt && !(Mode == VcmMode::vcm && plan.merges == Merges::every));
    pixel_start_.resize(plan.seen.size());
    for (size_t p = 0; p < pixel_start_.size(); ++p)
      pixel_start_[p] = KVcmPixel{plan.seen[p], 0, 0};
    film_shift_ = fixed_point_shift(scene_.data(), film_.cmf(), film_.spectral());
    const size_t pixels = film_.pixels(), bins = s.scene.grid.bins;
    if (paths_ > (1u << 31) - 1) throw Error("vcm: at most 2^31 - 1 pixels");
    fixed_ = device_buffer(cl_, cells() * 2 * sizeof(cl_ulong), "vcm: the light paths' film");
    counters_ = device_buffer(cl_, sizeof(KVcmCounters), "vcm: the light pass's counters");
    pixels_ = device_buffer(cl_, pixels * sizeof(KVcmPixel), "vcm: the pixels' records");
    // A chunk of light subpaths has a record each (KVcmLightPath): at most as many as the store
    // holds vertices, so that --photons grows no buffer beyond the --memory budget.
    chunk_paths_ = std::max<size_t>(1, std::min(paths_, budget_ / record_bytes()));
    light_paths_ =
        device_buffer(cl_, chunk_paths_ * sizeof(KVcmLightPath), "vcm: the chunk's light subpaths");
    // Connections compute a light vertex's f·Φ into a spectrum of the camera path's own, and
    // its surface (textured, coated) into scratch of its own (kernels/vcm/vcm_modes.h,
    // VCM_SPECTRA).
    spectra_floats_ =
        Mode == VcmMode::ppm ? 0 : bins + static_cast<size_t>(scratch_floats(s.scene));
    spectra_ = device_buffer(cl_, std::max<size_t>(pixels * spectra_floats_, 1) * sizeof(cl_float),
                             "vcm: per-path spectra");
    cell_ = device_buffer(cl_, 2 * sizeof(cl_float), "vcm: the grid's cell size");
    fixed_before_ =
        device_buffer(cl_, cells() * 2 * sizeof(cl_ulong), "vcm: the light paths' film");
    // ~4 stored vertices a light path in ordinary scenes.
    if (!allocate_store(std::max<size_t>(4 * paths_, 1024)) && capacity_ == 0)
      throw Error("--memory: " + std::to_string(budget_) + " bytes hold no light vertex (" +
                  std::to_string(record_bytes()) + " bytes each)");
  }

 public:
  PassResult render_pass(int pass) override {
    const auto t0 = std::chrono::steady_clock::now();
    const double device0 = device_seconds_;
    const Radius radius = radius_of(pass);
    const size_t pixels = film_.pixels();
    film_.clear_pixel_sums();
    cl_.queue().enqueueFillBuffer(fixed_, cl_ulong(0), 0, cells() * 2 * sizeof(cl_ulong));
    // Each pixel's seen-light flag and zero tallies (pixel_start_ lives as long as the queue's
    // work on it: the write need not wait).
    cl_.queue().enqueueWriteBuffer(pixels_, CL_FALSE, 0, pixels * sizeof(KVcmPixel),
                                   pixel_start_.data());
    overflow_ = 0;
    // The light subpaths in chunks of path ranges, each traced into the store and met by every
    // camera path (the same paths again): one chunk while the store holds the iteration, so
    // memory stays bounded however long light paths get and however many --photons asks for.
    Stages stages;
    size_t first = 0, count = paths_, done = pixels, chunks = 0;
    bool interrupted = false;
    while (first < paths_ && !interrupted) {
      count = std::min(count, paths_ - first);
      // A chunk never has more subpaths than the chunk's table holds (they could not all store a
      // vertex in a store of that size): the halving below, without tracing.
      while (count > chunk_paths_) count = (count + 1) / 2;
      double t = device_seconds_;
      // Path tracing alone (a test hook) needs no light subpaths.
      const Chunk chunk =
          emission_only_ ? no_light_paths(count) : trace_chunk(pass, radius, first, count);
      stages.light += device_seconds_ - t;
      if (chunk.outcome == Chunk::interrupted) {
        interrupted = true;
        break;
      }
      if (chunk.outcome == Chunk::too_big) {
        if (count == 1)
          throw Error("--memory: " + std::to_string(budget_) +
                      " bytes do not hold one light subpath's vertices; give more --memory");
        count = (count + 1) / 2;
        continue;
      }
      stages.stored += static_cast<double>(chunk.stored);
      stages.light_cut += read_light_cut(count);
      t = device_seconds_;
      if (Mode != VcmMode::bpt) {
        const float cell[2] = {static_cast<float>(radius.cell()),
                               static_cast<float>(1 / radius.cell())};
        cl_.queue().enqueueWriteBuffer(cell_, CL_TRUE, 0, sizeof(cell), cell);
        grid_->build(store_, chunk.stored, cell_);
      }
      stages.grid += device_seconds_ - t;
      const bool last = first + count >= paths_;
      done = camera_pass(pass, radius, first, first + count, last);
      // Ctrl-C during a chunk's camera pass that is not the last: no pixel has met every chunk.
      if (!last && done < pixels) interrupted = true;
      first += count;
      ++chunks;
    }
    if (interrupted) done = 0;
    PassResult r{pass, spp_, {}, film_.read_pixel_sums(), static_cast<double>(done) / pixels,
                 {},   {}};
    add_light_splats(r, done);
    if (done < pixels) {
      std::fill(r.sums.begin() + done * film_.rows(), r.sums.end(), 0.0);
      r.samples = 0;
      r.pixel_samples.assign(pixels, 0);
      std::fill(r.pixel_samples.begin(), r.pixel_samples.begin() + done, spp_);
    }
    add_counters(r, radius, stages, chunks);
    PassCounters& c = r.counters;
    c.add_stage("camera pass", device_seconds_ - device0 - stages.light - stages.grid);
    c.add_stage("host", std::max(0.0, seconds_since(t0) - (device_seconds_ - device0)));
    add_ray_counts(r);
    return r;
  }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels()) * spp_;
  }
  long long photons_per_pass() const override { return static_cast<long long>(paths_); }
  std::map<std::string, size_t> device_buffers() const override {
    std::map<std::string, size_t> b{
        {"light-vertex store", capacity_ * record_floats_ * sizeof(float)},
        {"light paths' film", cells() * 2 * sizeof(cl_ulong)},
        {"per-path tables", chunk_paths_ * sizeof(KVcmLightPath)},
        {"per-path spectra", film_.pixels() * spectra_floats_ * sizeof(float)},
        {"pixels' records", film_.pixels() * sizeof(KVcmPixel)}};
    if (grid_) b["hashed grid"] = grid_->bytes(capacity_);
    return b;
  }

 private:
  size_t cells() const { return film_.pixels() * film_.rows(); }
  size_t record_bytes() const {
    return record_floats_ * sizeof(float) + (Mode == VcmMode::bpt ? 0 : kPlacedGridBytesPerRecord);
  }

  // An iteration's merging radius (KVcmRadius, kernels/shared/vcm_records.h), computed in double
  // and rounded to float only in the launch's record: η per r² (κ π L over the camera paths a
  // pixel has — their merges at one pixel's vertices meet the same photons, so together they
  // count as one camera path's), the global radius or the per-path radii's cap, and the per-path
  // radii's footprint per unit of distance (0: the global radius).
  struct Radius {
    double eta_unit, radius, per_unit;
    // The hashed grid's cell: a query meets 2 × 2 × 2 cells at the global radius (or the per-path
    // radius at the typical distance, half the cap), at most 3 × 3 × 3 at the cap.
    double cell() const { return per_unit > 0 ? radius : 2 * radius; }
  };

  // Georgiev's global schedule, from the iteration's index alone.
  Radius radius_of(int pass) const {
    const double shrink = std::pow(pass + 1.0, (alpha_ - 1) / 2);
    return Radius{kMergeWeight * M_PI * static_cast<double>(paths_) / spp_, first_radius_ * shrink,
                  per_path_ ? footprint_ * shrink : 0};
  }

  // What a launch of either pass takes (KVcmIteration) for the store's chunk [first, end).
  KVcmIteration iteration(int pass, const Radius& radius, size_t first, size_t end) const {
    KVcmIteration it{};
    it.radius = KVcmRadius{static_cast<float>(radius.eta_unit), static_cast<float>(radius.radius),
                           static_cast<float>(radius.per_unit)};
    it.inv_cell = static_cast<float>(1 / radius.cell());
    it.mask = grid_ ? grid_->mask() : 0u;
    it.paths = static_cast<int>(paths_);
    it.chunk_first = static_cast<int>(first);
    it.chunk_end = static_cast<int>(end);
    it.capacity = static_cast<int>(capacity_);
    it.spp = spp_;
    it.seen_samples = kSeenLightSamples;
    it.film_shift = film_shift_;
    it.seed = seed_;
    it.pass = static_cast<uint>(pass);
    return it;
  }

  // Where a pass's device time went, and what its chunks stored and cut.
  struct Stages {
    double light = 0, grid = 0;  // seconds
    double stored = 0;           // light vertices
    double light_cut = 0;        // the depth guard's tally over the light subpaths
  };

  // How a chunk of light subpaths went: stored whole, too big for the store within the budget,
  // or cut by Ctrl-C.
  struct Chunk {
    enum Outcome { stored_whole, too_big, interrupted } outcome = stored_whole;
    size_t stored = 0;  // vertices
  };

  // The light subpaths' splats are one more term of every camera path's estimate: added to the
  // pixel's sums as many times as it has camera paths. A pass cut short keeps the pixels its last
  // camera pass reached.
  void add_light_splats(PassResult& r, size_t done) {
    std::vector<cl_ulong> fixed(2 * cells());
    cl_.queue().enqueueReadBuffer(fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_ulong),
                                  fixed.data());
    const size_t kept = done * film_.rows();
    for (size_t i = 0; i < kept; ++i)
      r.sums[i] += static_cast<double>(spp_) *
                   fixed_point_value(fixed[2 * i], fixed[2 * i + 1], film_shift_);
  }

  void add_counters(PassResult& r, const Radius& radius, const Stages& stages, size_t chunks) {
    const size_t pixels = film_.pixels();
    std::vector<KVcmPixel> px(pixels);
    cl_.queue().enqueueReadBuffer(pixels_, CL_TRUE, 0, pixels * sizeof(KVcmPixel), px.data());
    double rejected = 0, camera_cut = 0;
    for (const KVcmPixel& p : px) rejected += p.rejected, camera_cut += p.cut;
    PassCounters& c = r.counters;
    c.rejected_samples = rejected + overflow_;
    c.light_vertices_stored = stages.stored;
    c.light_chunks = static_cast<double>(chunks);
    c.merging_radius = per_path_ ? radius.radius / 2 : radius.radius;  // a typical one
    c.depth_guard = {stages.light_cut, static_cast<double>(paths_)};
    c.camera_depth_guard = {camera_cut, static_cast<double>(pixels) * spp_};
    c.add_stage("light pass", stages.light);
    c.add_stage("grid", stages.grid);
  }

  // The depth guard's tally over the chunk's `count` light subpaths.
  double read_light_cut(size_t count) {
    std::vector<KVcmLightPath> paths(count);
    cl_.queue().enqueueReadBuffer(light_paths_, CL_TRUE, 0, count * sizeof(KVcmLightPath),
                                  paths.data());
    double cut = 0;
    for (const KVcmLightPath& p : paths) cut += p.cut;
    return cut;
  }

  // The first radius: one pixel's footprint at the distance a camera path typically travels to
  // its merging vertex (merging_distance.h), else at the centre of the scene's bounds; --radius
  // sets it. `per_path` (without --radius): each camera path's radius is the footprint at its own
  // distance, capped at twice the typical one (first_radius_ is the cap then). Within the bounds
  // photon mapping keeps (render/merge_radius.h).
  void set_first_radius(const Scene& scene, double distance, double radius, bool per_path) {
    const MergeRadiusBounds bounds = merge_radius_bounds(scene, scene_.data().camera);
    const double largest = bounds.largest;
    if (radius > 0) distance = 0;
    if (!(distance > 0)) distance = bounds.centre_distance;
    per_path_ = per_path && radius <= 0;
    footprint_ = bounds.footprint;
    first_radius_ = radius > 0 ? radius : footprint_ * distance * (per_path_ ? 2 : 1);
    if (first_radius_ > largest) {
      if (radius > 0) warn_radius_beyond(radius, bounds);
      first_radius_ = largest;
    }
    if (!(first_radius_ > 0)) first_radius_ = largest > 0 ? largest : 1;
  }

  // A store of `records` light vertices (and the grid over it), within the memory budget; false
  // when the store is already as large as the budget allows.
  bool allocate_store(size_t records) {
    const size_t most = budget_ / record_bytes();
    if (records > most) {
      if (capacity_ >= most) return false;
      records = most;
    }
    capacity_ = records;
    store_ = device_buffer(cl_, capacity_ * record_floats_ * sizeof(float),
                           "vcm: the light-vertex store (--memory)");
    KernelLauncher& device = *this;  // the grid launches its kernels through it
    if (Mode != VcmMode::bpt) grid_.emplace(device, program_, capacity_, /*placed*/ true);
    return true;
  }

  // Light subpaths [first, first + count) of the iteration into the emptied store, splatting to
  // the light paths' film. A store too small for them grows (within the budget) and the chunk
  // runs again with the same random numbers, its splats taken back; too_big: the chunk does not
  // fit the budget. A chunk is cut as soon as the store overflows (the rest could not fit either)
  // and at Ctrl-C, between launches.
  Chunk trace_chunk(int pass, const Radius& radius, size_t first, size_t count) {
    cl_.queue().enqueueCopyBuffer(fixed_, fixed_before_, 0, 0, cells() * 2 * sizeof(cl_ulong));
    for (;;) {
      const KVcmIteration it = iteration(pass, radius, first, first + count);
      KVcmCounters counters{0, 0};
      cl_.queue().enqueueWriteBuffer(counters_, CL_TRUE, 0, sizeof counters, &counters);
      size_t done = 0;
      while (done < count && fits(counters)) {
        if (interrupt_requested()) return Chunk{Chunk::interrupted, 0};
        const size_t n = light_pacer_.next(count - done);
        const auto t = std::chrono::steady_clock::now();
        launch_range(light_kernel_, first + done, n, it, store_, counters_, light_paths_, fixed_,
                     pixels_);
        light_pacer_.record(n, seconds_since(t));
        done += n;
        cl_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof counters, &counters);
        control_.report(0.5 * static_cast<double>(first + done) / paths_);
      }
      if (fits(counters)) {
        overflow_ += counters.overflow;
        return Chunk{Chunk::stored_whole, static_cast<size_t>(counters.stored)};
      }
      // The retried chunk's splats are taken back.
      cl_.queue().enqueueCopyBuffer(fixed_before_, fixed_, 0, 0, cells() * 2 * sizeof(cl_ulong));
      const size_t wanted =
          counters.stored < 0 ? SIZE_MAX / 2 : static_cast<size_t>(counters.stored);
      if (!allocate_store(wanted + wanted / 4)) return Chunk{Chunk::too_big, 0};
    }
  }

  bool fits(const KVcmCounters& c) const {
    return c.stored >= 0 && static_cast<size_t>(c.stored) <= capacity_;
  }

  // The camera pass with the store's chunk [first, end) of light subpaths; returns the pixels
  // done. Only the last chunk's pass may stop early at a deadline: every pixel it reached has met
  // every chunk. Ctrl-C stops any chunk's.
  size_t camera_pass(int pass, const Radius& radius, size_t first, size_t end, bool last) {
    const size_t pixels = film_.pixels();
    const KVcmIteration it = iteration(pass, radius, first, end);
    size_t done = 0;
    while (done < pixels) {
      // A deadline stops an iteration only once one has run whole (the first compiles the
      // kernels at its first launches: cut there, most pixels would have no sample at all).
      if (last && done > 0 && (whole_ > 0 || interrupt_requested()) && control_.stop_now()) break;
      if (!last && interrupt_requested()) break;
      const size_t n = camera_pacer_.next(pixels - done);
      const auto t = std::chrono::steady_clock::now();
      if (grid_)
        launch_range(camera_kernel_, done, n, it, store_, light_paths_, grid_->placed(),
                     grid_->cell_end(), spectra_, film_.pixel_sums(), pixels_);
      else
        launch_range(camera_kernel_, done, n, it, store_, light_paths_, spectra_,
                     film_.pixel_sums(), pixels_);
      camera_pacer_.record(n, seconds_since(t));
      done += n;
      if (last) control_.report(0.5 + 0.5 * static_cast<double>(done) / pixels);
    }
    if (last && done == pixels) ++whole_;
    return done;
  }

  // Path tracing alone (a test hook): the chunk's subpaths store nothing.
  Chunk no_light_paths(size_t count) {
    cl_.queue().enqueueFillBuffer(light_paths_, KVcmLightPath{-1, 0.0f}, 0,
                                  count * sizeof(KVcmLightPath));
    return Chunk{Chunk::stored_whole, 0};
  }

  double alpha_;
  unsigned seed_;
  int spp_;  // camera paths a pixel per iteration
  bool emission_only_;
  int whole_ = 0;  // iterations that ran whole
  size_t paths_;   // light subpaths per iteration: pixel p's camera path connects to the p-th
  size_t record_floats_;
  size_t spectra_floats_ = 0;  // a camera path's spectra (kernels/vcm/vcm_modes.h, VCM_SPECTRA)
  size_t budget_ = 0, capacity_ = 0;
  size_t chunk_paths_ = 0;   // the most light subpaths a chunk holds (its KVcmLightPath table)
  double first_radius_ = 0;  // the global radius, or (per_path_) the per-path radii's cap
  double footprint_ = 0;     // a pixel's footprint per unit of distance
  bool per_path_ = false;    // each camera path's radius from its distance (Radius::per_unit)
  int film_shift_ = 0;
  double overflow_ = 0;                 // the pass's splats the light paths' film rejected
  std::vector<KVcmPixel> pixel_start_;  // each pixel's record at a pass's start
  // Camera launches of 0.05 s: a deadline cuts an iteration at a finer grain of pixels.
  LaunchPacer light_pacer_{0.2, 256}, camera_pacer_{0.05, 256};
  cl::Kernel light_kernel_, camera_kernel_;
  cl::Buffer store_, fixed_, fixed_before_, counters_, light_paths_, pixels_, spectra_, cell_;
  std::optional<HashGrid> grid_;
};

using VertexConnectionMerging = VcmIntegrator<VcmMode::vcm>;
using BidirectionalPathTracing = VcmIntegrator<VcmMode::bpt>;
using ProgressivePhotonMapping = VcmIntegrator<VcmMode::ppm>;

// The options of each mode, their defaults from the constants above; in this order in the
// registry's refusal ("it takes …").
static std::vector<IntegratorOption> vcm_options(VcmMode m) {
  using V = IntegratorOption::Value;
  const std::string caustic_lit = " where caustics light most of what the camera sees";
  std::vector<IntegratorOption> o;
  o.push_back({"--photons", V::integer, 1, 2147483647, "light subpaths per pass",
               m == VcmMode::ppm ? "one a pixel, at least " + number_text(kLeastPhotonMappingPaths)
               : m == VcmMode::vcm
                   ? "one a pixel, " + number_text(kCausticLitLightPaths) + " a pixel" +
                         caustic_lit + ", " + number_text(kScatteringLightPaths) +
                         " a pixel in scenes with scattering media"
                   : "one a pixel",
               KASHA_SETTING(photons)});
  if (m != VcmMode::bpt) {
    o.push_back({"--alpha", V::number, 0.01, 0.99, "SPPM's radius reduction α",
                 number_text(IntegratorSettings::kDefaultAlpha), KASHA_SETTING(alpha)});
    o.push_back({"--radius", V::positive, 0, 1e300, "initial gather radius",
                 "from the pixel footprint", KASHA_SETTING(radius)});
  }
  o.push_back({"--memory", V::bytes, 1, 1125899906842624.0 /* 2^50 */,
               "memory for the light-vertex store, bytes with an optional unit (512MiB, 2GB)",
               "a quarter of the device's memory, an eighth on a CPU", KASHA_SETTING(memory),
               /*device's own*/ true});
  const std::string spp = std::to_string(kDefaultCameraPaths) + ", " +
                          std::to_string(kCausticCameraPaths) +
                          " where mirrors, glass or smooth coats are";
  o.push_back({"--spp", V::integer, 1, 1 << 20, "camera samples per pixel per pass",
               m == VcmMode::ppm ? std::to_string(kDefaultPhotonMappingCameraPaths)
               : m == VcmMode::bpt
                   ? spp
                   : spp + ", " + std::to_string(kCausticLitCameraPaths) + caustic_lit,
               KASHA_SETTING(spp)});
  if (m == VcmMode::vcm)
    o.push_back({"--merges", V::choice, 0, 0,
                 "merge at the first camera vertex that is not delta only the light that came "
                 "through a mirror or glass (caustic), all light there (first, as SPPM gathers), "
                 "or all light at every such vertex (every, Georgiev et al.'s VCM)",
                 "auto: first" + caustic_lit + ", else caustic", KASHA_SETTING(merges)});
  if (m != VcmMode::bpt)
    o.push_back({"--edge-correction", V::flag, 0, 0,
                 "divide the density by the measured fraction of the gather discs on accepted "
                 "surface (--edge-correction=false leaves it out)",
                 "on", KASHA_SETTING(edge_correction)});
  return o;
}

KASHA_REGISTER_INTEGRATOR(
    VertexConnectionMerging, "vcm",
    "vertex connection and merging: light and camera subpaths joined by connections and merges "
    "under one MIS weight, iterations independent (a global radius schedule)",
    vcm_options(VcmMode::vcm),
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ false, /*samples seen light*/ true});
KASHA_REGISTER_INTEGRATOR(
    BidirectionalPathTracing, "bpt",
    "bidirectional path tracing: vcm's connections alone (next-event estimation, light "
    "tracing, subpath connections), MIS-weighted",
    vcm_options(VcmMode::bpt),
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ false, /*samples seen light*/ true});
KASHA_REGISTER_INTEGRATOR(
    ProgressivePhotonMapping, "ppm",
    "progressive photon mapping: vcm's merges alone, unweighted, at each camera path's first "
    "non-delta vertex",
    vcm_options(VcmMode::ppm),
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ true, /*samples seen light*/ true,
                     /*medium light paths*/ true});

}  // namespace kasha
