#pragma once
// `--integrator forward`: light tracing of kernels/forward.cl (DESIGN §2.1). A pass traces
// `photons` photons carrying the lights' total power; its splats are one estimate of the image.
#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/integrator.h"

namespace kasha {

// Power bookkeeping of the photons of the passes so far (W, summed over passes).
struct PhotonLedger {
  double emitted = 0, absorbed = 0, escaped = 0, in_flight = 0;
};

class ForwardIntegrator : public Integrator {
 public:
  // `max_depth` cuts photon paths (tests of the bookkeeping); the default is the kernel's guard.
  // `photons_per_item`: how many photons one work item traces (the image does not depend on it).
  ForwardIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene, const Film& film,
                    long long photons_per_pass, unsigned seed, int max_depth = 1000,
                    int photons_per_item = 64);
  std::string name() const override { return "forward"; }
  void render_pass(int pass, Film& film) override;
  long long camera_paths_per_pass() const override { return 0; }
  long long photons_per_pass() const override { return photons_; }
  long long rejected_samples() const override { return overflow_; }
  const PhotonLedger& ledger() const { return ledger_; }

 private:
  ClContext& cl_;
  DeviceScene& scene_;
  KCamera camera_;
  long long photons_;
  unsigned seed_;
  int max_depth_, photons_per_item_;
  size_t pixels_, rows_, items_;
  float bin_nm_, film_scale_;
  long long overflow_ = 0;
  PhotonLedger ledger_;
  cl::Kernel kernel_;
  cl::Buffer cmf_, film_, stats_, overflow_buffer_;
};

}  // namespace kasha
