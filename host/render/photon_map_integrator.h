#pragma once
// `--integrator photon` (the default): bidirectional photon mapping, progressive as stochastic
// progressive photon mapping (Hachisuka & Jensen 2009). Each pass: a camera pass storing one
// visible point per pixel, a photon pass storing photons at Lambert hits, a kd-tree over them and
// a gather; per pixel the radius shrinks as R' = R·sqrt((n + αm)/(n + m)) and the flux is scaled by
// R'²/R². The estimate is direct/k + τ/(k·π·R²·Δλ) after k passes. With edge correction (opt-in),
// each pass's flux is divided by the fraction of its gather disc on accepted surface
// (render/disc_coverage.h).
#include <memory>
#include <vector>

#include "geometry/embree_scene.h"
#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/integrator.h"

namespace kasha {

struct PhotonMapSettings {
  long long photons = 1 << 18;  // per pass
  double alpha = 2.0 / 3.0;
  double radius = 0;  // > 0: the initial radius everywhere; else from the pixel footprint
  unsigned seed = 1;
  bool edge_correction = false;  // divide each pass's flux by its disc's covered fraction
};

// Where a pass's time went, in seconds, summed over passes.
struct PhotonMapTimes {
  double photon_tracing = 0, kd_tree = 0, camera_pass = 0, gather = 0;
};

// Bytes of one stored photon and of one visible point for this scene and film.
size_t photon_record_bytes(const Scene& scene);
size_t visible_point_bytes(const Scene& scene, bool spectral_film);

class PhotonMapIntegrator : public Integrator {
 public:
  PhotonMapIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                      const Film& film, const PhotonMapSettings& settings);
  std::string name() const override { return "photon"; }
  void render_pass(int pass, Film& film) override;
  long long camera_paths_per_pass() const override { return static_cast<long long>(pixels_); }
  long long photons_per_pass() const override { return settings_.photons; }
  const PhotonMapTimes& times() const { return times_; }
  // The visible-point buffer's size on the device, and the stored photons of the last pass.
  size_t visible_point_buffer_bytes() const { return pixels_ * vp_floats_ * sizeof(float); }
  size_t last_stored_photons() const { return last_stored_; }

 private:
  void trace_photons(int pass, std::vector<float>& photons);

  ClContext& cl_;
  DeviceScene& scene_;
  const Scene& host_scene_;
  KCamera camera_;
  PhotonMapSettings settings_;
  size_t pixels_, rows_;
  int bins_, photon_floats_, vp_floats_;
  bool fluorescent_, spectral_;
  float bin_nm_;
  double footprint_;  // pixel width on the image plane at unit distance
  size_t capacity_, last_stored_ = 0;
  cl::Kernel photon_kernel_, camera_kernel_;
  cl::Buffer cmf_, importance_, store_, counter_, vps_, direct_;
  std::vector<float> cmf_host_;
  std::unique_ptr<EmbreeScene> embree_;  // probes the gather discs' coverage
  // Per-pixel progressive statistics.
  std::vector<double> radius_, count_, tau_, direct_sum_;
  PhotonMapTimes times_;
};

}  // namespace kasha
