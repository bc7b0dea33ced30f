#include "study/furnace.h"

#include <cmath>

#include "color/cie_observer.h"
#include "geometry/embree_scene.h"

namespace kasha {

static Furnace refuse(const std::string& why) {
  Furnace f;
  f.why_not = why;
  return f;
}

Furnace analyze_furnace(const Scene& scene) {
  const int material = scene.shapes.front().material;
  for (const ShapeInfo& s : scene.shapes) {
    if (s.material != material) return refuse("its shapes have different materials");
    if ((s.type != "box" && s.type != "sphere") || !s.inward)
      return refuse("a " + s.type + " shape is not a closed inward box or sphere");
    if (s.emitter < 0) return refuse("a shape does not emit");
  }
  const std::vector<double>& le = scene.emitters.at(scene.shapes.front().emitter).per_bin;
  for (const Emitter& e : scene.emitters)
    for (size_t i = 0; i < le.size(); ++i)
      if (std::abs(e.per_bin[i] - le[i]) > 1e-9 * std::max(1.0, std::abs(le[i])))
        return refuse("its shapes emit different spectra");
  const Material& m = scene.materials[material];
  if (m.gloss && !m.gloss->mirror) return refuse("its gloss lobe is not an ideal mirror");
  if (m.specular()) return refuse("its material is a dielectric or conductor");
  if (m.mix) return refuse("its material is a mix");

  // The camera must be inside: its corner and centre rays all meet a front (inner) face.
  EmbreeScene embree(scene.triangles);
  KCamera cam = scene.camera.to_kernel();
  for (float sx : {-1.0f, 0.0f, 1.0f})
    for (float sy : {-1.0f, 0.0f, 1.0f}) {
      KRay r{};
      float len = 0;
      for (int k = 0; k < 3; ++k) {
        r.org[k] = cam.position[k];
        r.dir[k] = cam.forward[k] + sx * cam.right[k] + sy * cam.up[k];
        len += r.dir[k] * r.dir[k];
      }
      for (float& d : r.dir) d /= std::sqrt(len);
      r.tmax = INFINITY;
      KHit h = embree.intersect(r);
      if (h.prim < 0) return refuse("the camera sees out of the enclosure");
      const KTriangle& t = scene.triangles[h.prim];
      float e1[3], e2[3], n[3];
      for (int k = 0; k < 3; ++k) e1[k] = t.v1[k] - t.v0[k], e2[k] = t.v2[k] - t.v0[k];
      n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2],
      n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      if (n[0] * r.dir[0] + n[1] * r.dir[1] + n[2] * r.dir[2] >= 0)
        return refuse("the camera is outside the enclosure");
    }

  const size_t N = le.size();
  const double g = m.gloss_reflectance();
  std::vector<double> binv_le(N), binv_e(N, 0.0);
  for (size_t i = 0; i < N; ++i) {
    double b = 1.0 - g - (m.rho.empty() ? 0.0 : m.rho[i]);
    if (!(b > 0))
      return refuse("1 − g − ρ is not positive at bin " + std::to_string(i) + " (no absorption)");
    binv_le[i] = le[i] / b;
    if (m.fluorescent()) binv_e[i] = m.e_hat[i] / b;
  }
  double a_binv_le = 0, a_binv_e = 0;
  if (m.fluorescent())
    for (size_t i = 0; i < N; ++i) a_binv_le += m.a[i] * binv_le[i], a_binv_e += m.a[i] * binv_e[i];
  if (!(a_binv_e < 1)) return refuse("aᵀB⁻¹ê >= 1: the enclosure has no steady state");
  Furnace f;
  f.qualifies = true;
  f.radiance.resize(N);
  for (size_t i = 0; i < N; ++i)
    f.radiance[i] = binv_le[i] + binv_e[i] * a_binv_le / (1 - a_binv_e);
  return f;
}

Image furnace_image(const Scene& scene, const std::vector<double>& radiance, bool spectral) {
  Image img;
  img.width = scene.camera.width;
  img.height = scene.camera.height;
  img.grid = scene.grid;
  BinnedObserver obs(scene.grid);
  auto xyz = obs.xyz(radiance, scene.grid.bin_nm);
  for (size_t p = 0; p < img.pixels(); ++p) {
    for (int k = 0; k < 3; ++k) img.xyz.push_back(static_cast<float>(xyz[k]));
    if (spectral)
      for (double v : radiance) img.spectral.push_back(static_cast<float>(v));
  }
  return img;
}

}  // namespace kasha
