#include "render/photon_map_integrator.h"

#include <chrono>
#include <cmath>

#include "core/error.h"
#include "opencl/upload.h"
#include "photon_layout.h"
#include "render/backward_integrator.h"
#include "render/disc_coverage.h"
#include "render/photon_gather.h"

namespace kasha {

namespace {
constexpr int kPhotonsPerItem = 64;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

size_t photon_record_bytes(const Scene& scene) {
  return KASHA_PHOTON_FLOATS(scene.grid.bins) * sizeof(float);
}

size_t visible_point_bytes(const Scene& scene, bool spectral_film) {
  int rows = spectral_film ? scene.grid.bins : 3;
  return KASHA_VP_FLOATS(scene.grid.bins, rows, scene.fluorescent()) * sizeof(float);
}

PhotonMapIntegrator::PhotonMapIntegrator(ClContext& cl, const Scene& scene,
                                         DeviceScene& device_scene, const Film& film,
                                         const PhotonMapSettings& settings)
    : cl_(cl),
      scene_(device_scene),
      host_scene_(scene),
      camera_(scene.camera.to_kernel()),
      settings_(settings),
      pixels_(film.pixels()),
      rows_(film.rows()),
      bins_(scene.grid.bins),
      photon_floats_(KASHA_PHOTON_FLOATS(scene.grid.bins)),
      vp_floats_(
          KASHA_VP_FLOATS(scene.grid.bins, static_cast<int>(film.rows()), scene.fluorescent())),
      fluorescent_(scene.fluorescent()),
      spectral_(film.spectral()),
      bin_nm_(static_cast<float>(scene.grid.bin_nm)) {
  if (settings.photons > (1LL << 31) - 1)
    throw Error("--photons: at most 2^31 - 1 photons per pass");
  if (!(settings.alpha > 0 && settings.alpha < 1)) throw Error("--alpha must lie in (0, 1)");
  if (device_scene.data().light_tri.empty())
    throw Error("photon: the scene has no emitter with power");
  cl::Program program = build_program(cl, assemble_kernel_source("photon_map.cl"),
                                      scene_defines(scene, film.spectral()), "photon_map.cl");
  photon_kernel_ = cl::Kernel(program, "trace_photon_map");
  camera_kernel_ = cl::Kernel(program, "camera_pass");
  cmf_host_ = film.cmf_weights();
  cmf_ = upload(cl, cmf_host_);
  std::vector<float> u = branch_importance(film);
  importance_ = upload(cl, u);
  counter_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(cl_int));
  vps_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, pixels_ * vp_floats_ * sizeof(float));
  direct_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, pixels_ * rows_ * sizeof(float));
  // Room for a few stored photons each; a pass that needs more is traced again with more room.
  capacity_ = static_cast<size_t>(settings.photons) * 4;
  store_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, capacity_ * photon_floats_ * sizeof(float));
  footprint_ = 2.0 *
               std::sqrt(camera_.up[0] * camera_.up[0] + camera_.up[1] * camera_.up[1] +
                         camera_.up[2] * camera_.up[2]) /
               camera_.height;
  if (settings.edge_correction) embree_ = std::make_unique<EmbreeScene>(scene.triangles);
  radius_.assign(pixels_, 0.0);
  count_.assign(pixels_, 0.0);
  tau_.assign(pixels_ * rows_, 0.0);
  direct_sum_.assign(pixels_ * rows_, 0.0);
}

void PhotonMapIntegrator::trace_photons(int pass, std::vector<float>& photons) {
  const KernelSceneData& d = scene_.data();
  const size_t items = (settings_.photons + kPhotonsPerItem - 1) / kPhotonsPerItem;
  for (;;) {
    cl_.queue().enqueueFillBuffer(counter_, cl_int(0), 0, sizeof(cl_int));
    int a = 0;
    a = scene_.bind(photon_kernel_, a);
    photon_kernel_.setArg(a++, bin_nm_);
    photon_kernel_.setArg(a++, d.ray_eps);
    photon_kernel_.setArg(a++, static_cast<int>(settings_.photons));
    photon_kernel_.setArg(a++, kPhotonsPerItem);
    photon_kernel_.setArg(a++, store_);
    photon_kernel_.setArg(a++, counter_);
    photon_kernel_.setArg(a++, static_cast<int>(capacity_));
    photon_kernel_.setArg(a++, settings_.seed);
    photon_kernel_.setArg(a++, static_cast<unsigned>(pass));
    cl_.queue().enqueueNDRangeKernel(photon_kernel_, cl::NullRange, cl::NDRange(items),
                                     cl::NullRange);
    cl_int stored = 0;
    cl_.queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &stored);
    if (stored >= 0 && static_cast<size_t>(stored) <= capacity_) {
      last_stored_ = stored;
      photons.resize(static_cast<size_t>(stored) * photon_floats_);
      if (stored > 0)
        cl_.queue().enqueueReadBuffer(store_, CL_TRUE, 0, photons.size() * sizeof(float),
                                      photons.data());
      return;
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

void PhotonMapIntegrator::render_pass(int pass, Film& film) {
  const KernelSceneData& d = scene_.data();
  auto t0 = Clock::now();
  int a = 0;
  camera_kernel_.setArg(a++, camera_);
  a = scene_.bind(camera_kernel_, a);
  camera_kernel_.setArg(a++, cmf_);
  camera_kernel_.setArg(a++, importance_);
  camera_kernel_.setArg(a++, d.ray_eps);
  camera_kernel_.setArg(a++, vps_);
  camera_kernel_.setArg(a++, direct_);
  camera_kernel_.setArg(a++, settings_.seed);
  camera_kernel_.setArg(a++, static_cast<unsigned>(pass));
  cl_.queue().enqueueNDRangeKernel(camera_kernel_, cl::NullRange, cl::NDRange(pixels_),
                                   cl::NullRange);
  std::vector<float> vps(pixels_ * vp_floats_), direct(pixels_ * rows_);
  cl_.queue().enqueueReadBuffer(vps_, CL_TRUE, 0, vps.size() * sizeof(float), vps.data());
  cl_.queue().enqueueReadBuffer(direct_, CL_TRUE, 0, direct.size() * sizeof(float), direct.data());
  times_.camera_pass += since(t0);

  auto t1 = Clock::now();
  std::vector<float> photons;
  trace_photons(pass, photons);
  times_.photon_tracing += since(t1);

  auto t2 = Clock::now();
  PhotonKdTree tree(photons.data(), photons.size() / photon_floats_, photon_floats_);
  times_.kd_tree += since(t2);

  auto t3 = Clock::now();
  // A pixel's first visible point sets its initial radius: one pixel width at its distance.
  for (size_t p = 0; p < pixels_; ++p) {
    const float* vp = &vps[p * vp_floats_];
    if (radius_[p] == 0 && vp[KASHA_VP_VALID] != 0)
      radius_[p] = settings_.radius > 0 ? settings_.radius : footprint_ * vp[KASHA_VP_DISTANCE];
  }
  PhotonGatherLayout layout{bins_, static_cast<int>(rows_), fluorescent_, spectral_,
                            cmf_host_.data()};
  GatherResult g = tree.gather(vps.data(), vp_floats_, pixels_, radius_, layout);
  if (embree_) {
    // A fresh rotation of the probe pattern each pass, so its stratification leaves no pattern.
    float rotation = static_cast<float>(
        2 * M_PI * std::fmod(0.6180339887 * (pass + 1) + 1e-3 * settings_.seed, 1.0));
    std::vector<float> coverage =
        disc_coverage(*embree_, vps.data(), vp_floats_, pixels_, radius_, rotation);
    for (size_t p = 0; p < pixels_; ++p)
      for (size_t r = 0; r < rows_; ++r) g.flux[p * rows_ + r] /= coverage[p];
  }

  const double alpha = settings_.alpha, k = pass + 1;
  std::vector<double> estimate(pixels_ * rows_);
  for (size_t p = 0; p < pixels_; ++p) {
    for (size_t r = 0; r < rows_; ++r) direct_sum_[p * rows_ + r] += direct[p * rows_ + r];
    const int m = g.found[p];
    if (m > 0) {
      // SPPM: keep a fraction α of the new photons and shrink the radius to match.
      double n_new = count_[p] + alpha * m;
      double r_new = radius_[p] * std::sqrt(n_new / (count_[p] + m));
      double shrink = (r_new * r_new) / (radius_[p] * radius_[p]);
      for (size_t r = 0; r < rows_; ++r)
        tau_[p * rows_ + r] = (tau_[p * rows_ + r] + g.flux[p * rows_ + r]) * shrink;
      count_[p] = n_new;
      radius_[p] = r_new;
    }
    double area = radius_[p] > 0 ? M_PI * radius_[p] * radius_[p] : 1.0;
    for (size_t r = 0; r < rows_; ++r)
      estimate[p * rows_ + r] =
          direct_sum_[p * rows_ + r] / k + tau_[p * rows_ + r] / (k * area * bin_nm_);
  }
  film.set_estimate(estimate, pass + 1);
  times_.gather += since(t3);
}

}  // namespace kasha
