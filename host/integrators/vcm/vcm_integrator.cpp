// `--integrator vcm`, `bpt` and `ppm`: vertex connection and merging (kernels/vcm.cl; Georgiev
// et al. 2012, SmallVCM's vertexcm.hxx) and the two modes that share its kernels — connections
// only (bidirectional path tracing) and merges only (progressive photon mapping, unweighted) —
// each built with only the code it uses. An iteration is a light pass (a light subpath per
// pixel, its vertices stored and splatted to the camera), the hashed grid over the stored
// vertices (render/hash_grid.h), and a camera pass (one path per pixel). The merging radius
// follows a global schedule r_i = r_1 · i^((α−1)/2), so an iteration depends on nothing but its
// index and the seed: iterations are passes the ordered scheduler hands to any device or MPI rank,
// and the image is the same bit for bit however they are shared (docs/integrators.md).
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "integrators/forward/fixed_point_film.h"
#include "integrators/vcm/merging_distance.h"
#include "integrators/vcm/seen_light.h"
#include "opencl/device_buffer.h"
#include "render/hash_grid.h"
#include "render/kernel_integrator.h"
#include "render/launch_pacer.h"
#include "vcm_layout.h"

namespace kasha {

namespace {

enum class VcmMode { vcm, bpt, ppm };

// Light subpaths per iteration unless --photons says (default_light_paths): one a pixel in vcm
// and bpt, as SmallVCM (a pixel's camera paths connect to their own; with fewer than pixels ·
// spp, sample j of pixel p takes (p · spp + j) mod their count). More mostly lengthen the light
// pass: on the 32² furnaces, 2^14 of them (16 a pixel) left bpt 1.0–1.5 × backward's RMSE at 8 s,
// one a pixel 0.65–0.8 ×. ppm, merges alone, takes direct light from them too: at least this many.
constexpr size_t kLeastPhotonMappingPaths = 1 << 16;
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
// Camera paths a pixel per iteration unless --spp says: several share an iteration's light pass
// in vcm and bpt (measured: vcm's RMSE after 20 s on the Cornell box 0.00081 with four against
// 0.00097 with one, bpt's 0.00074 against 0.00084). Eight where no light bounces off a mirror,
// glass or a smooth coat — vcm is bpt there, and its light subpaths serve only connections and
// light tracing (bpt's RMSE after 12 s, 8 against 4: the Cornell box −11 %, the light booth
// −13 %, a million triangles −6 %); four where caustics are, whose merges and light tracing need
// fresh photons more than more camera paths (the mirror caustic +28 % with eight). ppm, whose
// estimate is all merges with the one photon map, gains nothing from more.
constexpr int kDefaultCameraPaths = 8;
// Samples per camera path of the light seen through delta bounces alone (a lamp, its image in
// glass, a mirror or a coat; kernels/vcm.cl, vcm_seen_light), in the pixels where it has an edge
// (seen_light.h). Its MIS weight is 1, so any number is unbiased; each costs a ray or a few, a
// camera path tens. Measured (vcm, RMSE after 20 s against none): the lacquered vase's highlight
// −54 %, the glass of water −51 %, the glass caustic −46 %, a million triangles −17 %, the Cornell
// box −7 %; 16 gained 0–6 % more on those, none elsewhere (docs/integrators.md).
constexpr int kSeenLightSamples = 8;
constexpr int kCausticCameraPaths = 4;
// Probes of a merge's disc for the edge correction (kernels/disc_coverage.h), once a merge has
// met a photon; each is a short ray through the gather's slab.
constexpr int kCoverageProbes = 8;
constexpr int kDefaultPhotonMappingCameraPaths = 1;

// A caustic-lit view: the scene has delta surfaces and most merging vertices see no lamp
// (`unlit`, merging_distance.h), so what the camera sees is lit by caustics and the light they
// bring on, which merges and light tracing alone reach. There vcm runs as photon mapping does —
// --merges auto merges all light at the first vertex (`first`: next to a wall, the light the
// wall throws on the floor comes from connections alone under `caustic`, whose 1/d² near the
// corner leaves it short at 20 s: 0.29 against 0.35) — and with light subpaths for merges before
// camera paths: 2 camera paths a pixel unless --spp says, and 32 light subpaths a pixel whatever
// --spp says (capped at 2^31 − 1). bpt, which does not merge, gains nothing from more
// (the mirror caustic +7 % with 4 a pixel). Measured on the mirror caustic (vcm --merges first,
// RMSE after 20 s against the mean of 120-s photon-mapping and 300-s vcm renders): 4 camera paths
// and 4 light subpaths a pixel 0.0139, 4 and 16 0.0104, 4 and 32 0.0097, 4 and 64 0.0095, 2 and
// 32 0.0092, 2 and 64 0.0093, 1 and 32 0.0104; photon mapping 0.0098. The counts go with `first`:
// an explicit --merges caustic or every keeps those of other views. Elsewhere more light subpaths
// lengthen the light pass: the mirror furnace, lit directly everywhere, +9 % with 4 a pixel and +23
// % with 16.
constexpr double kMostlyUnlit = 0.5;
constexpr int kCausticLitCameraPaths = 2;
constexpr size_t kCausticLitLightPaths = 32;

size_t default_light_paths(VcmMode m, size_t pixels, bool caustic_lit) {
  if (m == VcmMode::ppm) return std::max<size_t>(pixels, kLeastPhotonMappingPaths);
  if (m == VcmMode::vcm && caustic_lit)
    return std::min<size_t>(pixels * kCausticLitLightPaths, (1u << 31) - 1);
  return pixels;
}

int default_camera_paths(VcmMode m, const Scene& scene, bool caustic_lit) {
  if (m == VcmMode::ppm) return kDefaultPhotonMappingCameraPaths;
  if (m == VcmMode::vcm && caustic_lit) return kCausticLitCameraPaths;
  return scene.has_delta_surfaces() ? kCausticCameraPaths : kDefaultCameraPaths;
}

// What vcm takes from camera rays on the host (Embree) before its kernels are built: where
// camera paths merge, whether the view is caustic-lit, what merges, and the pixels where the
// light seen through delta bounces alone has an edge (seen_light.h).
struct VcmPlan {
  MergingVertices merging;
  bool caustic_lit = false;  // a caustic-lit view merging all light at the first vertex
  std::string merges;        // --merges, `auto` resolved: caustic, first or every
  std::vector<int> seen;     // per pixel: 1 where that light has an edge
};

VcmPlan plan_for(VcmMode m, const IntegratorSetup& s) {
  VcmPlan p;
  const EmbreeScene embree(s.scene.triangles);
  const KCamera& camera = s.device_scene.data().camera;
  p.merging = probe_merging_vertices(s.scene, embree, camera);
  const bool caustic_lit =
      m == VcmMode::vcm && s.scene.has_delta_surfaces() && p.merging.unlit > kMostlyUnlit;
  p.merges = s.settings.merges != "auto" ? s.settings.merges : caustic_lit ? "first" : "caustic";
  p.caustic_lit = caustic_lit && p.merges == "first";  // the counts go with all light merged
  p.seen = s.settings.vcm_no_seen_light ? std::vector<int>(s.film.pixels(), 0)
                                        : seen_light_pixels(s.scene, embree, camera);
  return p;
}

KernelDefines mode_defines(VcmMode m, const IntegratorSettings& s, const std::string& merges) {
  KernelDefines d{{"KASHA_VCM_CONNECT", m == VcmMode::ppm ? "0" : "1"},
                  {"KASHA_VCM_MERGE", m == VcmMode::bpt ? "0" : "1"}};
  if (m == VcmMode::vcm && merges == "every") d["KASHA_VCM_MERGE_EVERY"] = "1";
  if (m == VcmMode::vcm && merges == "caustic") d["KASHA_VCM_MERGE_CAUSTIC"] = "1";
  if (m != VcmMode::bpt && s.edge_correction) {
    d["KASHA_VCM_EDGE_CORRECTION"] = "1";
    d["KASHA_VCM_COVERAGE_PROBES"] = std::to_string(kCoverageProbes);
  }
  // The test hooks (kernels/vcm.cl), only when set.
  if (s.vcm_length > 0) d["KASHA_VCM_LENGTH"] = std::to_string(s.vcm_length);
  if (s.vcm_emission_only) d["KASHA_VCM_EMISSION_ONLY"] = "1";
  if (s.vcm_drop_density) d["KASHA_VCM_DROP_DENSITY"] = "1";
  return d;
}

}  // namespace

template <VcmMode Mode>
class VcmIntegrator : public KernelIntegrator {
 public:
  explicit VcmIntegrator(const IntegratorSetup& s) : VcmIntegrator(s, plan_for(Mode, s)) {}

 private:
  VcmIntegrator(const IntegratorSetup& s, const VcmPlan& plan)
      : KernelIntegrator(s, "vcm.cl", mode_defines(Mode, s.settings, plan.merges)),
        alpha_(s.settings.alpha),
        seed_(s.settings.seed),
        spp_(s.settings.spp > 0 ? s.settings.spp
                                : default_camera_paths(Mode, s.scene, plan.caustic_lit)),
        emission_only_(s.settings.vcm_emission_only),
        record_floats_(KASHA_VCM_FLOATS(s.scene.grid.bins)),
        bins_(s.scene.grid.bins),
        light_kernel_(program_, "vcm_light_pass"),
        camera_kernel_(program_, "vcm_camera_pass") {
    if (!(alpha_ > 0 && alpha_ < 1)) throw Error("--alpha must lie in (0, 1)");
    budget_ = s.settings.memory > 0 ? static_cast<size_t>(s.settings.memory)
                                    : default_memory_budget(cl_.info());
    paths_ = s.settings.photons > 0 ? static_cast<size_t>(s.settings.photons)
                                    : default_light_paths(Mode, film_.pixels(), plan.caustic_lit);
    set_first_radius(s.scene, Mode != VcmMode::bpt ? plan.merging.distance : 0, s.settings.radius,
                     Mode != VcmMode::bpt && !(Mode == VcmMode::vcm && plan.merges == "every"));
    const std::vector<int>& seen = plan.seen;
    seen_pixels_ = device_buffer(cl_, seen.size() * sizeof(cl_int), "vcm: the pixels seeing light");
    cl_.queue().enqueueWriteBuffer(seen_pixels_, CL_TRUE, 0, seen.size() * sizeof(cl_int),
                                   seen.data());
    film_shift_ = fixed_point_shift(scene_.data(), film_.cmf(), film_.spectral());
    const size_t pixels = film_.pixels(), bins = s.scene.grid.bins;
    if (paths_ > (1u << 31) - 1) throw Error("vcm: at most 2^31 - 1 pixels");
    fixed_ = device_buffer(cl_, cells() * 2 * sizeof(cl_ulong), "vcm: the light paths' film");
    stored_ = device_buffer(cl_, sizeof(cl_int), "vcm: the store's counter");
    overflow_ = device_buffer(cl_, sizeof(cl_int), "vcm: the rejected splats' counter");
    path_last_ = device_buffer(cl_, paths_ * sizeof(cl_int), "vcm: the light paths' ends");
    light_cut_ = device_buffer(cl_, paths_ * sizeof(cl_float), "vcm: depth-guard tallies");
    camera_cut_ = device_buffer(cl_, pixels * sizeof(cl_float), "vcm: depth-guard tallies");
    rejected_ = device_buffer(cl_, pixels * sizeof(cl_int), "vcm: rejected counts");
    // Connections compute a light vertex's f·Φ into a spectrum of the camera path's own, and
    // its surface (textured, coated) into scratch of its own (kernels/vcm.cl, VCM_SPECTRA).
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
    // The iteration's radius (or the per-path radii's footprint and cap): Georgiev's global
    // schedule, from the iteration's index alone.
    const double shrink = std::pow(pass + 1.0, (alpha_ - 1) / 2);
    const Radius radius{kMergeWeight * M_PI * static_cast<double>(paths_) / spp_,
                        first_radius_ * shrink, per_path_ ? footprint_ * shrink : 0};
    const size_t pixels = film_.pixels();
    film_.clear_pixel_sums();
    cl_.queue().enqueueFillBuffer(fixed_, cl_ulong(0), 0, cells() * 2 * sizeof(cl_ulong));
    cl_.queue().enqueueFillBuffer(overflow_, cl_int(0), 0, sizeof(cl_int));
    cl_.queue().enqueueFillBuffer(rejected_, cl_int(0), 0, pixels * sizeof(cl_int));
    cl_.queue().enqueueFillBuffer(light_cut_, cl_float(0), 0, paths_ * sizeof(cl_float));
    cl_.queue().enqueueFillBuffer(camera_cut_, cl_float(0), 0, pixels * sizeof(cl_float));
    // The light subpaths in chunks of path ranges, each traced into the store and met by every
    // camera path (the same paths again): one chunk while the store holds the iteration, so
    // memory stays bounded however long light paths get.
    double light_s = 0, grid_s = 0, stored_total = 0;
    size_t first = 0, count = paths_, done = pixels, chunks = 0;
    while (first < paths_) {
      count = std::min(count, paths_ - first);
      double t = device_seconds_;
      // Path tracing alone (a test hook) needs no light subpaths.
      const std::optional<size_t> stored =
          emission_only_ ? no_light_paths() : trace_chunk(pass, radius, first, count);
      light_s += device_seconds_ - t;
      if (!stored) {
        if (count == 1)
          throw Error("--memory: " + std::to_string(budget_) +
                      " bytes do not hold one light subpath's vertices; give more --memory");
        count = (count + 1) / 2;
        continue;
      }
      stored_total += static_cast<double>(*stored);
      t = device_seconds_;
      if (Mode != VcmMode::bpt) {
        const float cell[2] = {static_cast<float>(radius.cell()),
                               static_cast<float>(1 / radius.cell())};
        cl_.queue().enqueueWriteBuffer(cell_, CL_TRUE, 0, sizeof(cell), cell);
        grid_->build(store_, *stored, cell_);
      }
      grid_s += device_seconds_ - t;
      const bool last = first + count >= paths_;
      done = camera_pass(pass, radius, first, first + count, last);
      first += count;
      ++chunks;
    }
    PassResult r{pass, spp_, {}, film_.read_pixel_sums(), static_cast<double>(done) / pixels,
                 {},   {}};
    // The light subpaths' splats are one more term of every camera path's estimate: added to the
    // pixel's sums as many times as it has camera paths. A pass cut short keeps the pixels its
    // last camera pass reached.
    std::vector<cl_ulong> fixed(2 * cells());
    cl_.queue().enqueueReadBuffer(fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_ulong),
                                  fixed.data());
    const size_t kept = done * film_.rows();
    for (size_t i = 0; i < kept; ++i)
      r.sums[i] += static_cast<double>(spp_) *
                   fixed_point_value(fixed[2 * i], fixed[2 * i + 1], film_shift_);
    if (done < pixels) {
      std::fill(r.sums.begin() + kept, r.sums.end(), 0.0);
      r.samples = 0;
      r.pixel_samples.assign(pixels, 0);
      std::fill(r.pixel_samples.begin(), r.pixel_samples.begin() + done, spp_);
    }
    PassCounters& c = r.counters;
    c.rejected_samples = read_sum<cl_int>(rejected_, pixels) + read_sum<cl_int>(overflow_, 1);
    c.light_vertices_stored = stored_total;
    c.light_chunks = static_cast<double>(chunks);
    c.merging_radius = per_path_ ? radius.radius / 2 : radius.radius;  // a typical one
    c.depth_guard = {read_sum<cl_float>(light_cut_, paths_), static_cast<double>(paths_)};
    c.camera_depth_guard = {read_sum<cl_float>(camera_cut_, pixels),
                            static_cast<double>(pixels) * spp_};
    c.add_stage("light pass", light_s);
    c.add_stage("grid", grid_s);
    c.add_stage("camera pass", device_seconds_ - device0 - light_s - grid_s);
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
        {"per-path tables", paths_ * 2 * sizeof(cl_int) + film_.pixels() * 2 * sizeof(float)},
        {"per-path spectra", film_.pixels() * spectra_floats_ * sizeof(float)},
        {"pixels seeing light's edges", film_.pixels() * sizeof(cl_int)}};
    if (grid_) b["hashed grid"] = grid_->bytes(capacity_);
    return b;
  }

 private:
  size_t cells() const { return film_.pixels() * film_.rows(); }
  size_t record_bytes() const {
    return record_floats_ * sizeof(float) + (Mode == VcmMode::bpt ? 0 : kPlacedGridBytesPerRecord);
  }

  // An iteration's merging radius (kernels/vcm.cl, VcmRadius): η per r² (κ π L over the camera
  // paths a pixel has — their merges at one pixel's vertices meet the same photons, so together
  // they count as one camera path's), the global radius or the per-path radii's cap, and the
  // per-path radii's footprint per unit of distance (0: the global radius).
  struct Radius {
    double eta_unit, radius, per_unit;
    // The hashed grid's cell: a query meets 2 × 2 × 2 cells at the global radius (or the per-path
    // radius at the typical distance, half the cap), at most 3 × 3 × 3 at the cap.
    double cell() const { return per_unit > 0 ? radius : 2 * radius; }
  };

  // The first radius: one pixel's footprint at the distance a camera path typically travels to
  // its merging vertex (merging_distance.h), else at the centre of the scene's bounds; --radius
  // sets it. `per_path` (without --radius): each camera path's radius is the footprint at its own
  // distance, capped at twice the typical one (first_radius_ is the cap then). Within a fiftieth
  // of the scene's diagonal as photon mapping's.
  void set_first_radius(const Scene& scene, double distance, double radius, bool per_path) {
    const KCamera& c = scene_.data().camera;
    const double footprint =
        2.0 * std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]) / c.height;
    Eigen::AlignedBox3d box;
    for (const KTriangle& t : scene.triangles)
      for (const float* v : {t.v0, t.v1, t.v2}) box.extend(Eigen::Vector3d(v[0], v[1], v[2]));
    const Eigen::Vector3d eye(c.position[0], c.position[1], c.position[2]);
    const double largest = box.diagonal().norm() / 50;
    if (radius > 0) distance = 0;
    if (!(distance > 0)) distance = (box.center() - eye).norm();
    per_path_ = per_path && radius <= 0;
    footprint_ = footprint;
    first_radius_ = radius > 0 ? radius : footprint * distance * (per_path_ ? 2 : 1);
    if (first_radius_ > largest) {
      if (radius > 0)
        warn("--radius " + std::to_string(radius) +
             " is beyond 1/50 of the scene's diagonal; using " + std::to_string(largest));
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
  // runs again with the same random numbers, its splats taken back; nothing: the chunk does not
  // fit the budget. Returns the vertices stored.
  std::optional<size_t> trace_chunk(int pass, const Radius& radius, size_t first, size_t count) {
    cl_.queue().enqueueCopyBuffer(fixed_, fixed_before_, 0, 0, cells() * 2 * sizeof(cl_ulong));
    cl_int overflow_before = 0;
    cl_.queue().enqueueReadBuffer(overflow_, CL_TRUE, 0, sizeof(cl_int), &overflow_before);
    for (;;) {
      cl_.queue().enqueueFillBuffer(stored_, cl_int(0), 0, sizeof(cl_int));
      size_t done = 0;
      while (done < count) {
        const size_t n = light_pacer_.next(count - done);
        const auto t = std::chrono::steady_clock::now();
        launch_range(light_kernel_, first + done, n, static_cast<cl_int>(paths_),
                     static_cast<cl_float>(radius.eta_unit), static_cast<cl_float>(radius.radius),
                     static_cast<cl_float>(radius.per_unit), store_, stored_,
                     static_cast<cl_int>(capacity_), path_last_, fixed_,
                     static_cast<cl_int>(film_shift_), overflow_, light_cut_,
                     static_cast<cl_int>(spp_), seed_, static_cast<cl_uint>(pass));
        light_pacer_.record(n, seconds_since(t));
        done += n;
        control_.report(0.5 * static_cast<double>(first + done) / paths_);
      }
      cl_int stored = 0;
      cl_.queue().enqueueReadBuffer(stored_, CL_TRUE, 0, sizeof(cl_int), &stored);
      if (stored >= 0 && static_cast<size_t>(stored) <= capacity_)
        return static_cast<size_t>(stored);
      // The retried chunk's splats and rejected splats are taken back.
      cl_.queue().enqueueCopyBuffer(fixed_before_, fixed_, 0, 0, cells() * 2 * sizeof(cl_ulong));
      cl_.queue().enqueueWriteBuffer(overflow_, CL_TRUE, 0, sizeof(cl_int), &overflow_before);
      const size_t wanted = stored < 0 ? SIZE_MAX / 2 : static_cast<size_t>(stored);
      if (!allocate_store(wanted + wanted / 4)) return std::nullopt;
    }
  }

  // The camera pass with the store's chunk [first, end) of light subpaths; returns the pixels
  // done. Only the last chunk's pass may stop early (a deadline, Ctrl-C): every pixel it reached
  // has met every chunk.
  size_t camera_pass(int pass, const Radius& radius, size_t first, size_t end, bool last) {
    const size_t pixels = film_.pixels();
    size_t done = 0;
    while (done < pixels) {
      // A deadline stops an iteration only once one has run whole (the first compiles the
      // kernels at its first launches: cut there, most pixels would have no sample at all).
      if (last && done > 0 && (whole_ > 0 || interrupt_requested()) && control_.stop_now()) break;
      const size_t n = camera_pacer_.next(pixels - done);
      const auto t = std::chrono::steady_clock::now();
      launch_range(camera_kernel_, done, n, static_cast<cl_int>(paths_), static_cast<cl_int>(first),
                   static_cast<cl_int>(end), static_cast<cl_float>(radius.eta_unit),
                   static_cast<cl_float>(radius.radius), static_cast<cl_float>(radius.per_unit),
                   store_, path_last_, grid_ ? grid_->placed() : path_last_,
                   grid_ ? grid_->cell_count() : path_last_, grid_ ? grid_->cell_end() : path_last_,
                   static_cast<cl_float>(1 / radius.cell()), grid_ ? grid_->mask() : 0u, spectra_,
                   film_.pixel_sums(), rejected_, camera_cut_, static_cast<cl_int>(spp_),
                   seen_pixels_, static_cast<cl_int>(kSeenLightSamples), seed_,
                   static_cast<cl_uint>(pass));
      camera_pacer_.record(n, seconds_since(t));
      done += n;
      if (last) control_.report(0.5 + 0.5 * static_cast<double>(done) / pixels);
    }
    if (last && done == pixels) ++whole_;
    return done;
  }

  size_t no_light_paths() {
    cl_.queue().enqueueFillBuffer(path_last_, cl_int(-1), 0, paths_ * sizeof(cl_int));
    return 0;
  }

  double alpha_;
  unsigned seed_;
  int spp_;  // camera paths a pixel per iteration
  bool emission_only_;
  int whole_ = 0;  // iterations that ran whole
  size_t paths_;   // light subpaths per iteration: pixel p's camera path connects to the p-th
  size_t record_floats_;
  size_t bins_;
  size_t spectra_floats_ = 0;  // a camera path's spectra (kernels/vcm.cl, VCM_SPECTRA)
  size_t budget_ = 0, capacity_ = 0;
  double first_radius_ = 0;  // the global radius, or (per_path_) the per-path radii's cap
  double footprint_ = 0;     // a pixel's footprint per unit of distance
  bool per_path_ = false;    // each camera path's radius from its distance (Radius::per_unit)
  int film_shift_ = 0;
  // Camera launches of 0.05 s: a deadline cuts an iteration at a finer grain of pixels.
  LaunchPacer light_pacer_{0.2, 256}, camera_pacer_{0.05, 256};
  cl::Kernel light_kernel_, camera_kernel_;
  cl::Buffer store_, fixed_, fixed_before_, stored_, overflow_, path_last_, light_cut_, camera_cut_,
      rejected_, spectra_, cell_, seen_pixels_;
  std::optional<HashGrid> grid_;
};

using VertexConnectionMerging = VcmIntegrator<VcmMode::vcm>;
using BidirectionalPathTracing = VcmIntegrator<VcmMode::bpt>;
using ProgressivePhotonMapping = VcmIntegrator<VcmMode::ppm>;

KASHA_REGISTER_INTEGRATOR(
    VertexConnectionMerging, "vcm",
    "vertex connection and merging: light and camera subpaths joined by connections and merges "
    "under one MIS weight, iterations independent (a global radius schedule)",
    {"--photons", "--alpha", "--radius", "--memory", "--spp", "--merges", "--edge-correction"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ false, /*samples seen light*/ true});
KASHA_REGISTER_INTEGRATOR(
    BidirectionalPathTracing, "bpt",
    "bidirectional path tracing: vcm's connections alone (next-event estimation, light "
    "tracing, subpath connections), MIS-weighted",
    {"--photons", "--memory", "--spp"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ false, /*samples seen light*/ true});
KASHA_REGISTER_INTEGRATOR(
    ProgressivePhotonMapping, "ppm",
    "progressive photon mapping: vcm's merges alone, unweighted, at each camera path's first "
    "non-delta vertex",
    {"--photons", "--alpha", "--radius", "--memory", "--spp", "--edge-correction"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false, /*direct by merges*/ true, /*samples seen light*/ true});

}  // namespace kasha
