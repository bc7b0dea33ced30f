#include "geometry/cl_traversal.h"

#include "opencl/kernel_program.h"
#include "opencl/upload.h"

namespace kasha {

ClTraversal::ClTraversal(ClContext& cl, const FlatBvh& bvh, const AlphaCutouts& alpha) : cl_(cl) {
  nodes_ = upload(cl, bvh.nodes);
  // Buffers may not be empty: without instances, one unread entry.
  instances_ = upload(cl, bvh.instances.empty() ? std::vector<KInstance>(1) : bvh.instances);
  leaves_ = upload(cl, bvh.leaves);
  triangles_ = upload(cl, bvh.triangles);
  // Without alpha, one unread entry each.
  std::vector<KTexcoords> texcoords(1);
  std::vector<KTexture> textures(1);
  std::vector<float> values(1);
  std::vector<KTexOp> ops(1);
  if (!alpha.empty()) {
    texcoords.clear();
    for (const KTriangle& t : bvh.triangles) texcoords.push_back(alpha.texcoords[t.prim]);
    if (!alpha.textures.empty()) textures = alpha.textures;
    if (!alpha.values.empty()) values = alpha.values;
    if (!alpha.ops.empty()) ops = alpha.ops;
  }
  texcoords_ = upload(cl, texcoords);
  textures_ = upload(cl, textures);
  values_ = upload(cl, values);
  ops_ = upload(cl, ops);
  KernelDefines defines;
  defines["KASHA_ALPHA"] = alpha.empty() ? "0" : "1";
  defines["KASHA_TEXTURE_PROGRAMS"] = alpha.ops.empty() ? "0" : "1";
  defines["KASHA_INSTANCES"] = bvh.instances.empty() ? "0" : "1";
  cl::Program program = build_program(cl, assemble_kernel_source("geometry/trace_rays.cl"), defines,
                                      "geometry/trace_rays.cl");
  closest_ = cl::Kernel(program, "trace_closest");
  occluded_ = cl::Kernel(program, "trace_occluded");
}

template <typename Out>
void ClTraversal::run(cl::Kernel& kernel, const std::vector<KRay>& rays, std::vector<Out>& out) {
  out.resize(rays.size());
  if (rays.empty()) return;
  if (rays.size() > ray_capacity_) {
    rays_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, rays.size() * sizeof(KRay));
    ray_capacity_ = rays.size();
  }
  if (rays.size() * sizeof(Out) > result_bytes_) {
    results_ = cl::Buffer(cl_.context(), CL_MEM_WRITE_ONLY, rays.size() * sizeof(Out));
    result_bytes_ = rays.size() * sizeof(Out);
  }
  cl_.queue().enqueueWriteBuffer(rays_, CL_FALSE, 0, rays.size() * sizeof(KRay), rays.data());
  kernel.setArg(0, nodes_);
  kernel.setArg(1, leaves_);
  kernel.setArg(2, instances_);
  kernel.setArg(3, triangles_);
  kernel.setArg(4, texcoords_);
  kernel.setArg(5, textures_);
  kernel.setArg(6, values_);
  kernel.setArg(7, ops_);
  kernel.setArg(8, rays_);
  kernel.setArg(9, results_);
  kernel.setArg(10, static_cast<int>(rays.size()));
  cl_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(rays.size()), cl::NullRange);
  cl_.queue().enqueueReadBuffer(results_, CL_TRUE, 0, rays.size() * sizeof(Out), out.data());
}

void ClTraversal::closest(const std::vector<KRay>& rays, std::vector<KHit>& hits) {
  run(closest_, rays, hits);
}
void ClTraversal::occluded(const std::vector<KRay>& rays, std::vector<int>& occluded) {
  run(occluded_, rays, occluded);
}
std::vector<KHit> ClTraversal::closest(const std::vector<KRay>& rays) {
  std::vector<KHit> hits;
  closest(rays, hits);
  return hits;
}
std::vector<int> ClTraversal::occluded(const std::vector<KRay>& rays) {
  std::vector<int> out;
  occluded(rays, out);
  return out;
}

}  // namespace kasha
