#include "geometry/cl_traversal.h"

#include "opencl/kernel_program.h"
#include "opencl/upload.h"

namespace kasha {

ClTraversal::ClTraversal(ClContext& cl, const FlatBvh& bvh) : cl_(cl) {
  nodes_ = upload(cl, bvh.nodes);
  triangles_ = upload(cl, bvh.triangles);
  cl::Program program =
      build_program(cl, assemble_kernel_source("trace_rays.cl"), {}, "trace_rays.cl");
  closest_ = cl::Kernel(program, "trace_closest");
  occluded_ = cl::Kernel(program, "trace_occluded");
}

template <typename Out>
std::vector<Out> ClTraversal::run(cl::Kernel& kernel, const std::vector<KRay>& rays) {
  std::vector<Out> out(rays.size());
  if (rays.empty()) return out;
  cl::Buffer in = upload(cl_, rays);
  cl::Buffer result(cl_.context(), CL_MEM_WRITE_ONLY, rays.size() * sizeof(Out));
  kernel.setArg(0, nodes_);
  kernel.setArg(1, triangles_);
  kernel.setArg(2, in);
  kernel.setArg(3, result);
  kernel.setArg(4, static_cast<int>(rays.size()));
  cl_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(rays.size()), cl::NullRange);
  cl_.queue().enqueueReadBuffer(result, CL_TRUE, 0, rays.size() * sizeof(Out), out.data());
  return out;
}

std::vector<KHit> ClTraversal::closest(const std::vector<KRay>& rays) {
  return run<KHit>(closest_, rays);
}
std::vector<int> ClTraversal::occluded(const std::vector<KRay>& rays) {
  return run<int>(occluded_, rays);
}

}  // namespace kasha
