// `--integrator debug`: first-hit views for checking a scene before rendering it for real.
// "emission" estimates the directly visible emitted radiance (an unbiased estimate of that term
// alone); "normals" shows geometric normals as colour; "albedo" the colour of each material's
// Lambert parts under equal-energy light, fluorescence included.
#include "core/error.h"
#include "render/kernel_integrator.h"

namespace kasha {

constexpr int kDebugSpp = 16;  // samples a pixel per pass unless --spp says

class DebugIntegrator : public KernelIntegrator {
 public:
  explicit DebugIntegrator(const IntegratorSetup& s)
      : KernelIntegrator(s, "debug/debug_render.cl"),
        view_(static_cast<int>(s.settings.view)),  // the kernel's view index: the enum's order
        spp_(s.settings.spp > 0 ? s.settings.spp : kDebugSpp),
        seed_(s.settings.seed),
        kernel_(program_, "render_debug") {
    if (film_.spectral() && s.settings.view != DebugView::emission)
      throw Error("--spectral: the " + choice_name(s.settings.view) +
                  " view has no spectrum; use --view emission");
  }

  PassResult render_pass(int pass) override {
    film_.clear_pixel_sums();
    launch(kernel_, film_.pixels(), film_.pixel_sums(), view_, spp_, seed_,
           static_cast<cl_uint>(pass));
    PassResult r{pass, spp_, {}, film_.read_pixel_sums(), 1.0, {}, {}};
    add_ray_counts(r);
    return r;
  }

  long long camera_paths_per_pass() const override {
    return static_cast<long long>(film_.pixels()) * spp_;
  }
  long long photons_per_pass() const override { return 0; }

 private:
  int view_, spp_;
  unsigned seed_;
  cl::Kernel kernel_;
};

KASHA_REGISTER_INTEGRATOR(DebugIntegrator, "debug",
                          "first-hit views of the scene: emission, normals or albedo (--view)",
                          {{"--spp", IntegratorOption::Value::integer, 1, 1 << 20,
                            "camera samples per pixel per pass", std::to_string(kDebugSpp),
                            KASHA_SETTING(spp)},
                           {"--view", IntegratorOption::Value::choice, 0, 0, "which first-hit view",
                            choice_name(IntegratorSettings().view), KASHA_SETTING(view)}},
                          IntegratorTraits{/*physical*/ false, /*unbiased*/ false,
                                           /*sees camera mirrors*/ false, /*reference*/ false});

}  // namespace kasha
