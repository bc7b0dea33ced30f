#pragma once
// `--integrator debug`: first-hit views for checking a scene before rendering it for real.
// "emission" estimates the directly visible emitted radiance (an unbiased estimate of that term
// alone); "normals" shows geometric normals as colour; "albedo" the colour of each material's
// Lambert parts under equal-energy light, fluorescence included.
#include <string>

#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/integrator.h"

namespace kasha {

enum class DebugView { emission = 0, normals = 1, albedo = 2 };
DebugView parse_debug_view(const std::string& name);  // throws kasha::Error for an unknown name

class DebugIntegrator : public Integrator {
 public:
  DebugIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene, const Film& film,
                  DebugView view, int spp, unsigned seed);
  std::string name() const override { return "debug"; }
  void render_pass(int pass, Film& film) override;
  long long camera_paths_per_pass() const override {
    return static_cast<long long>(pixels_) * spp_;
  }
  long long photons_per_pass() const override { return 0; }

 private:
  ClContext& cl_;
  DeviceScene& scene_;
  KCamera camera_;
  DebugView view_;
  int spp_;
  unsigned seed_;
  size_t pixels_, rows_;
  cl::Kernel kernel_;
  cl::Buffer cmf_, film_;
};

}  // namespace kasha
