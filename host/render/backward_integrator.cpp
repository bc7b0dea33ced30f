#include "render/backward_integrator.h"

#include <algorithm>

#include "opencl/upload.h"

namespace kasha {

std::vector<float> branch_importance(const Film& film) {
  std::vector<float> cmf = film.cmf_weights();
  const size_t n = cmf.size() / 3;
  std::vector<float> u(n);
  for (size_t i = 0; i < n; ++i) u[i] = cmf[i] + cmf[n + i] + cmf[2 * n + i];
  float peak = *std::max_element(u.begin(), u.end());
  for (float& v : u) v += 0.05f * peak;
  return u;
}

BackwardIntegrator::BackwardIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                                       const Film& film, int spp, unsigned seed, bool full_matrix)
    : cl_(cl),
      scene_(device_scene),
      camera_(scene.camera.to_kernel()),
      spp_(spp),
      seed_(seed),
      pixels_(film.pixels()),
      rows_(film.rows()) {
  KernelDefines defines = scene_defines(scene, film.spectral());
  if (full_matrix) defines["KASHA_FULL_MATRIX"] = "1";
  cl::Program program =
      build_program(cl, assemble_kernel_source("backward.cl"), defines, "backward.cl");
  kernel_ = cl::Kernel(program, "render_backward");
  cmf_ = upload(cl, film.cmf_weights());
  importance_ = upload(cl, branch_importance(film));
  film_ = cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY, pixels_ * rows_ * sizeof(float));
  rejected_buffer_ = cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY, pixels_ * sizeof(int));
}

void BackwardIntegrator::render_pass(int pass, Film& film) {
  const KernelSceneData& d = scene_.data();
  int a = 0;
  kernel_.setArg(a++, camera_);
  a = scene_.bind(kernel_, a);
  kernel_.setArg(a++, cmf_);
  kernel_.setArg(a++, importance_);
  kernel_.setArg(a++, d.ray_eps);
  kernel_.setArg(a++, film_);
  kernel_.setArg(a++, rejected_buffer_);
  kernel_.setArg(a++, spp_);
  kernel_.setArg(a++, seed_);
  kernel_.setArg(a++, static_cast<unsigned>(pass));
  cl_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(pixels_), cl::NullRange);
  std::vector<float> sums(pixels_ * rows_);
  std::vector<int> rejected(pixels_);
  cl_.queue().enqueueReadBuffer(film_, CL_TRUE, 0, sums.size() * sizeof(float), sums.data());
  cl_.queue().enqueueReadBuffer(rejected_buffer_, CL_TRUE, 0, rejected.size() * sizeof(int),
                                rejected.data());
  for (int r : rejected) rejected_ += r;
  film.add_pass(sums, spp_);
}

}  // namespace kasha
