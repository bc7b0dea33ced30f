#pragma once
// `--integrator backward`: the OpenCL camera path tracer of kernels/backward.cl (DESIGN §2.2).
#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/integrator.h"

namespace kasha {

// Per-bin weights that rank a path's branches by the energy they bring to the film: the
// colour-matching functions summed over X, Y, Z times the bin width, plus 5 % of their peak so
// bins no film row sees directly (UV feeding fluorescence, a spectral film's edges) keep a chance.
std::vector<float> branch_importance(const Film& film);

class BackwardIntegrator : public Integrator {
 public:
  // `full_matrix` builds the test-only reference that carries the whole rows × N matrix.
  BackwardIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene, const Film& film,
                     int spp, unsigned seed, bool full_matrix = false);
  std::string name() const override { return "backward"; }
  void render_pass(int pass, Film& film) override;
  long long camera_paths_per_pass() const override {
    return static_cast<long long>(pixels_) * spp_;
  }
  long long photons_per_pass() const override { return 0; }
  long long rejected_samples() const override { return rejected_; }

 private:
  ClContext& cl_;
  DeviceScene& scene_;
  KCamera camera_;
  int spp_;
  unsigned seed_;
  size_t pixels_, rows_;
  long long rejected_ = 0;
  cl::Kernel kernel_;
  cl::Buffer cmf_, importance_, film_, rejected_buffer_;
};

}  // namespace kasha
