// `--integrator backward`: the OpenCL camera path tracer of kernels/backward.cl (DESIGN §2.2).
// A pass is `spp` paths per pixel; the kernel's work items own their pixels and add to the film's
// per-pixel sums.
#include "render/kernel_integrator.h"

namespace kasha {

class BackwardIntegrator : public KernelIntegrator {
 public:
  explicit BackwardIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(
            s, "backward.cl",
            s.settings.full_matrix ? KernelDefines{{"KASHA_FULL_MATRIX", "1"}} : KernelDefines{}),
        spp_(s.settings.spp),
        seed_(s.settings.seed),
        kernel_(program_, "render_backward"),
        rejected_(cl_.context(), CL_MEM_WRITE_ONLY, film_.pixels() * sizeof(cl_int)),
        cut_(cl_.context(), CL_MEM_WRITE_ONLY, film_.pixels() * sizeof(cl_float)) {}

  PassResult render_pass(int pass) override {
    film_.clear_pixel_sums();
    launch(kernel_, film_.pixels(), film_.pixel_sums(), rejected_, cut_, spp_, seed_,
           static_cast<cl_uint>(pass));
    PassResult r{pass, spp_, film_.read_pixel_sums(), {}, {}};
    r.tallies["rejected samples"] = read_sum<cl_int>(rejected_, film_.pixels());
    r.tallies[kDepthGuardCut] = read_sum<cl_float>(cut_, film_.pixels());  // relative to a start
    r.tallies[kDepthGuardOf] = static_cast<double>(camera_paths_per_pass());
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
  cl::Kernel kernel_;
  cl::Buffer rejected_, cut_;
};

KASHA_REGISTER_INTEGRATOR(
    BackwardIntegrator, "backward",
    "camera paths with next-event estimation and MIS, diagonal/rank-1 path colour", {"--spp"},
    IntegratorTraits{/*physical*/ true, /*unbiased*/ true,
                     /*sees camera mirrors*/ true, /*reference*/ true});

}  // namespace kasha
