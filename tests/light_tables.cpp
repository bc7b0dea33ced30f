#include "light_tables.h"

#include <algorithm>
#include <cmath>

#include "kernel_harness.h"
#include "opencl/upload.h"

namespace kasha::test {

using Eigen::Vector3d;

LightTables light_tables(const std::vector<KTriangle>& tris, const std::vector<int>& emitting,
                         const std::vector<double>& power, int emitters) {
  LightTables t;
  t.light_tri = emitting;
  double total = 0, cdf = 0;
  for (double p : power) total += p;
  std::vector<float> area_pdf(emitters, 0.0f);
  for (size_t j = 0; j < emitting.size(); ++j) {
    t.light_cdf.push_back(static_cast<float>((cdf += power[j]) / total));
    const KTriangle& k = tris[emitting[j]];
    const Vector3d v0(k.v0[0], k.v0[1], k.v0[2]), v1(k.v1[0], k.v1[1], k.v1[2]),
        v2(k.v2[0], k.v2[1], k.v2[2]);
    area_pdf[k.emitter] =
        static_cast<float>(power[j] / total / (0.5 * (v1 - v0).cross(v2 - v0).norm()));
  }
  t.light_cdf.back() = 1.0f;
  t.bvh = build_light_bvh(tris, emitting, power);
  KSceneParams& p = t.params;
  p.light_count = p.light_triangles = static_cast<int>(emitting.size());
  p.bin_nm = 1.0f;
  const std::vector<float> zeros(4, 0.0f), radiance(4 * emitters, 1.0f);
  t.buffer = upload_tables(
      test_device(),
      {host_table(std::vector<KBvhNode>(1), p.nodes),
       host_table(std::vector<KBvhLeaf>(1), p.leaves), host_table(tris, p.tris),
       host_table(std::vector<KMaterial>(1), p.materials), host_table(zeros, p.spectra),
       host_table(zeros, p.lobes), host_table(radiance, p.emitter_radiance),
       host_table(area_pdf, p.emitter_area_pdf), host_table(t.light_tri, p.light_tri),
       host_table(t.light_cdf, p.light_cdf), host_table(std::vector<KLight>(1), p.lights),
       host_table(std::vector<KTexture>(1), p.textures),
       host_table(std::vector<KTexcoords>(1), p.texcoords),
       host_table(std::vector<KShadingNormals>(1), p.normals),
       host_table(t.bvh.nodes, p.light_nodes), host_table(t.bvh.trails, p.light_trails),
       host_table(std::vector<KSphereLight>(1), p.light_spheres)});
  return t;
}

double reference_importance(const KLightNode& n, const Vector3d& x) {
  const Vector3d lo(n.lo[0], n.lo[1], n.lo[2]), hi(n.hi[0], n.hi[1], n.hi[2]);
  const Vector3d w = Vector3d(n.w[0], n.w[1], n.w[2]).normalized();
  const Vector3d pc = (lo + hi) / 2, d = x - pc;
  const double dc2 = d.squaredNorm(), r2 = (hi - lo).squaredNorm() / 4;
  const double d2 = std::max(dc2, (hi - lo).norm() / 2);
  const double cos_w = dc2 > 0 ? w.dot(d) / std::sqrt(dc2) : 1.0;
  const double sin_w = std::sqrt(std::max(0.0, 1 - cos_w * cos_w));
  const double cos_b = dc2 < r2 ? -1.0 : std::sqrt(std::max(0.0, 1 - r2 / dc2));
  const double sin_b = std::sqrt(std::max(0.0, 1 - cos_b * cos_b));
  const double cos_o = n.cos_o, sin_o = std::sqrt(std::max(0.0, 1 - cos_o * cos_o));
  // pbrt-v4's cosSubClamped and sinSubClamped: θw − θo, then less θb, clamped at 0.
  const double cos_x = cos_w > cos_o ? 1.0 : cos_w * cos_o + sin_w * sin_o;
  const double sin_x = cos_w > cos_o ? 0.0 : sin_w * cos_o - cos_w * sin_o;
  const double cos_p = cos_x > cos_b ? 1.0 : cos_x * cos_b + sin_x * sin_b;
  return cos_p > 0 ? n.phi * cos_p / d2 : 0.0;
}

double reference_pick(const LightBvh& bvh, int j, const Vector3d& x) {
  std::uint64_t trail = bvh.trails[j];
  double pick = 1;
  int node = 0;
  while (bvh.nodes[node].child >= 0) {
    const int second = bvh.nodes[node].child;
    double c0 = reference_importance(bvh.nodes[node + 1], x),
           c1 = reference_importance(bvh.nodes[second], x);
    if (!(c0 + c1 > 0)) c0 = bvh.nodes[node + 1].phi, c1 = bvh.nodes[second].phi;  // by power
    pick *= (trail & 1 ? c1 : c0) / (c0 + c1);
    node = trail & 1 ? second : node + 1;
    trail >>= 1;
  }
  return pick;
}

}  // namespace kasha::test
