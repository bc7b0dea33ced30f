#include "render/forward_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "opencl/upload.h"

namespace kasha {

ForwardIntegrator::ForwardIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                                     const Film& film, long long photons_per_pass, unsigned seed,
                                     int max_depth, int photons_per_item)
    : cl_(cl),
      scene_(device_scene),
      camera_(scene.camera.to_kernel()),
      photons_(photons_per_pass),
      seed_(seed),
      max_depth_(max_depth),
      photons_per_item_(photons_per_item),
      pixels_(film.pixels()),
      rows_(film.rows()),
      items_((photons_per_pass + photons_per_item - 1) / photons_per_item),
      bin_nm_(static_cast<float>(scene.grid.bin_nm)) {
  if (photons_per_pass > (1LL << 31) - 1)
    throw Error("--photons: at most 2^31 - 1 photons per pass");
  if (device_scene.data().light_tri.empty())
    throw Error("forward: the scene has no emitter with power");
  cl::Program program = build_program(cl, assemble_kernel_source("forward.cl"),
                                      scene_defines(scene, film.spectral()), "forward.cl");
  kernel_ = cl::Kernel(program, "trace_forward");
  std::vector<float> cmf = film.cmf_weights();
  cmf_ = upload(cl, cmf);
  // Fixed point: the brightest emitter's film value maps to 2^32, leaving 2^31 of headroom per
  // pixel and pass and a resolution of 2^-32 of it.
  double brightest = 0;
  const std::vector<float>& le = device_scene.data().emitter_radiance;
  const int n = scene.grid.bins;
  for (size_t e = 0; e * n < le.size(); ++e)
    for (size_t r = 0; r < rows_; ++r) {
      double v = 0;
      for (int i = 0; i < n; ++i)
        v += (film.spectral() ? (static_cast<int>(r) == i) : cmf[r * n + i]) * le[e * n + i];
      brightest = std::max(brightest, v);
    }
  film_scale_ = static_cast<float>(std::ldexp(1.0, 32) / std::max(brightest, 1e-30));
  film_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, pixels_ * rows_ * sizeof(cl_long));
  stats_ = cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY, items_ * 4 * sizeof(float));
  overflow_buffer_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(int));
}

void ForwardIntegrator::render_pass(int pass, Film& film) {
  const KernelSceneData& d = scene_.data();
  cl_.queue().enqueueFillBuffer(film_, cl_long(0), 0, pixels_ * rows_ * sizeof(cl_long));
  cl_.queue().enqueueFillBuffer(overflow_buffer_, cl_int(0), 0, sizeof(cl_int));
  int a = 0;
  kernel_.setArg(a++, camera_);
  a = scene_.bind(kernel_, a);
  kernel_.setArg(a++, cmf_);
  kernel_.setArg(a++, bin_nm_);
  kernel_.setArg(a++, d.ray_eps);
  kernel_.setArg(a++, static_cast<int>(photons_));
  kernel_.setArg(a++, photons_per_item_);
  kernel_.setArg(a++, max_depth_);
  kernel_.setArg(a++, film_);
  kernel_.setArg(a++, film_scale_);
  kernel_.setArg(a++, stats_);
  kernel_.setArg(a++, overflow_buffer_);
  kernel_.setArg(a++, seed_);
  kernel_.setArg(a++, static_cast<unsigned>(pass));
  cl_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(items_), cl::NullRange);

  std::vector<cl_long> fixed(pixels_ * rows_);
  std::vector<float> stats(items_ * 4);
  cl_int overflow = 0;
  cl_.queue().enqueueReadBuffer(film_, CL_TRUE, 0, fixed.size() * sizeof(cl_long), fixed.data());
  cl_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, stats.size() * sizeof(float), stats.data());
  cl_.queue().enqueueReadBuffer(overflow_buffer_, CL_TRUE, 0, sizeof(cl_int), &overflow);
  overflow_ += overflow;
  for (size_t i = 0; i < items_; ++i) {
    ledger_.emitted += stats[4 * i];
    ledger_.absorbed += stats[4 * i + 1];
    ledger_.escaped += stats[4 * i + 2];
    ledger_.in_flight += stats[4 * i + 3];
  }
  std::vector<float> values(fixed.size());
  for (size_t i = 0; i < fixed.size(); ++i)
    values[i] = static_cast<float>(fixed[i] / static_cast<double>(film_scale_));
  film.add_pass(values, 1);  // the pass's splats are one estimate of every pixel
}

}  // namespace kasha
