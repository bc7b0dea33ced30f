// `--integrator photon` (the default): bidirectional photon mapping, progressive as stochastic
// progressive photon mapping (Hachisuka & Jensen 2009). Each pass: a camera pass storing one
// visible point per pixel (kernels/photon_map.cl), a photon pass storing photons at Lambert hits,
// a kd-tree over them and a gather on the host (photon_gather.h). The pass's result is the
// directly seen emission and, per pixel, the gather's radius, count and flux; the film turns
// those into SPPM statistics (film/sppm_statistics.h). With edge correction (opt-in), each
// pass's flux is divided by the fraction of its gather disc on accepted surface (disc_coverage.h).
#include <chrono>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "geometry/embree_scene.h"
#include "integrators/photon/disc_coverage.h"
#include "integrators/photon/photon_gather.h"
#include "integrators/photon/photon_records.h"
#include "render/kernel_integrator.h"

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
    counter_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, sizeof(cl_int));
    cut_ = cl::Buffer(cl_.context(), CL_MEM_WRITE_ONLY, photon_items() * sizeof(cl_float));
    vps_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, vp_bytes());
    // Room for a few stored photons each; a pass that needs more is traced again with more room.
    capacity_ = static_cast<size_t>(photons_) * 4;
    store_ =
        cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, capacity_ * photon_floats_ * sizeof(float));
    const KCamera& c = scene_.data().camera;
    footprint_ =
        2.0 * std::sqrt(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]) / c.height;
    if (s.settings.edge_correction) embree_ = std::make_unique<EmbreeScene>(s.scene.triangles);
  }

  PassResult render_pass(int pass) override {
    auto t0 = Clock::now();
    film_.clear_pixel_sums();
    launch(camera_kernel_, film_.pixels(), vps_, film_.pixel_sums(), seed_,
           static_cast<cl_uint>(pass));
    std::vector<float> vps(film_.pixels() * vp_floats_);
    cl_.queue().enqueueReadBuffer(vps_, CL_TRUE, 0, vp_bytes(), vps.data());
    PassResult r{pass, 1, film_.read_pixel_sums(), GatherPass{}, {}};
    r.tallies["time: camera pass (s)"] = since(t0);

    auto t1 = Clock::now();
    std::vector<float> photons = trace_photons(pass);
    r.tallies["time: photon tracing (s)"] = since(t1);
    r.tallies["photons stored"] = static_cast<double>(photons.size() / photon_floats_);
    r.tallies[kDepthGuardCut] = read_sum<cl_float>(cut_, photon_items());  // per photon's start
    r.tallies[kDepthGuardOf] = static_cast<double>(photons_);

    auto t2 = Clock::now();
    PhotonKdTree tree(photons.data(), photons.size() / photon_floats_, photon_floats_);
    r.tallies["time: kd-tree (s)"] = since(t2);

    auto t3 = Clock::now();
    GatherPass& g = *r.gather;
    g.alpha = alpha_;
    g.radius = accumulated_.photon_radius();
    g.radius.resize(film_.pixels(), 0.0);
    // A pixel's first visible point sets its initial radius: one pixel width at its distance.
    for (size_t p = 0; p < film_.pixels(); ++p) {
      const float* vp = &vps[p * vp_floats_];
      if (g.radius[p] == 0 && vp[KASHA_VP_VALID] != 0)
        g.radius[p] = radius_ > 0 ? radius_ : footprint_ * vp[KASHA_VP_DISTANCE];
    }
    GatherResult found = tree.gather(vps.data(), vp_floats_, film_.pixels(), g.radius, layout_);
    if (embree_) {
      // A fresh rotation of the probe pattern each pass, so its stratification leaves no pattern.
      float rotation =
          static_cast<float>(2 * M_PI * std::fmod(0.6180339887 * (pass + 1) + 1e-3 * seed_, 1.0));
      std::vector<float> coverage =
          disc_coverage(*embree_, vps.data(), vp_floats_, film_.pixels(), g.radius, rotation);
      for (size_t p = 0; p < film_.pixels(); ++p)
        for (int k = 0; k < film_.rows(); ++k) found.flux[p * film_.rows() + k] /= coverage[p];
    }
    g.flux = std::move(found.flux);
    g.found = std::move(found.found);
    r.tallies["time: gather (s)"] = since(t3);
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

  // The pass's stored photons, read back (photon_floats_ each).
  size_t photon_items() const { return (photons_ + kPhotonsPerItem - 1) / kPhotonsPerItem; }

  std::vector<float> trace_photons(int pass) {
    const size_t items = photon_items();
    for (;;) {
      cl_.queue().enqueueFillBuffer(counter_, cl_int(0), 0, sizeof(cl_int));
      launch(photon_kernel_, items, static_cast<cl_int>(photons_), kPhotonsPerItem, store_,
             counter_, static_cast<cl_int>(capacity_), cut_, seed_, static_cast<cl_uint>(pass));
      cl_int stored = 0;
      cl_.queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &stored);
      if (stored >= 0 && static_cast<size_t>(stored) <= capacity_) {
        std::vector<float> photons(static_cast<size_t>(stored) * photon_floats_);
        if (stored > 0)
          cl_.queue().enqueueReadBuffer(store_, CL_TRUE, 0, photons.size() * sizeof(float),
                                        photons.data());
        return photons;
      }
      // Not all photons fit: the same pass again (same random numbers) with room for them all.
      size_t wanted = stored > 0 ? static_cast<size_t>(stored) : capacity_ * 2;
      capacity_ = wanted + wanted / 4;
      if (capacity_ > (1u << 31) - 1)
        throw Error("photon: more than 2^31 photons stored in one pass; lower --photons");
      store_ =
          cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, capacity_ * photon_floats_ * sizeof(float));
    }
  }

  const Film& accumulated_;  // holds the SPPM radii the next gather uses
  long long photons_;
  double alpha_, radius_;
  unsigned seed_;
  int photon_floats_, vp_floats_;
  VertexFactorLayout layout_;
  double footprint_;  // pixel width on the image plane at unit distance
  size_t capacity_;
  cl::Kernel photon_kernel_, camera_kernel_;
  cl::Buffer store_, counter_, vps_, cut_;
  std::unique_ptr<EmbreeScene> embree_;  // probes the gather discs' coverage
};

KASHA_REGISTER_INTEGRATOR(
    PhotonMapIntegrator, "photon",
    "bidirectional photon mapping (SPPM): visible points with compact rank-1 factors, "
    "photons gathered on the host",
    {"--photons", "--alpha", "--radius", "--edge-correction"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ false, /*sees camera mirrors*/ true,
                     /*reference*/ false});

}  // namespace kasha
