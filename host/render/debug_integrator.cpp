#include "render/debug_integrator.h"

#include "core/error.h"
#include "opencl/upload.h"

namespace kasha {

DebugView parse_debug_view(const std::string& name) {
  if (name == "emission") return DebugView::emission;
  if (name == "normals") return DebugView::normals;
  if (name == "albedo") return DebugView::albedo;
  throw Error("--view " + name + ": unknown debug view (emission, normals, albedo)");
}

DebugIntegrator::DebugIntegrator(ClContext& cl, const Scene& scene, DeviceScene& device_scene,
                                 const Film& film, DebugView view, int spp, unsigned seed)
    : cl_(cl),
      scene_(device_scene),
      camera_(scene.camera.to_kernel()),
      view_(view),
      spp_(spp),
      seed_(seed),
      pixels_(film.pixels()),
      rows_(film.rows()) {
  if (film.spectral() && view != DebugView::emission)
    throw Error("--spectral: the " +
                std::string(view == DebugView::normals ? "normals" : "albedo") +
                " view has no spectrum; use --view emission");
  cl::Program program = build_program(cl, assemble_kernel_source("debug_render.cl"),
                                      scene_defines(scene, film.spectral()), "debug_render.cl");
  kernel_ = cl::Kernel(program, "render_debug");
  cmf_ = upload(cl, film.cmf_weights());
  film_ = cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY, pixels_ * rows_ * sizeof(float));
}

void DebugIntegrator::render_pass(int pass, Film& film) {
  int a = 0;
  kernel_.setArg(a++, camera_);
  a = scene_.bind(kernel_, a);
  kernel_.setArg(a++, cmf_);
  kernel_.setArg(a++, film_);
  kernel_.setArg(a++, static_cast<int>(view_));
  kernel_.setArg(a++, spp_);
  kernel_.setArg(a++, seed_);
  kernel_.setArg(a++, static_cast<unsigned>(pass));
  cl_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(pixels_), cl::NullRange);
  std::vector<float> sums(pixels_ * rows_);
  cl_.queue().enqueueReadBuffer(film_, CL_TRUE, 0, sums.size() * sizeof(float), sums.data());
  film.add_pass(sums, spp_);
}

}  // namespace kasha
