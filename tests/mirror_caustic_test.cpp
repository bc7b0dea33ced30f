// scenes/mirror_caustic.json: light reaches a diffuse surface only by a mirror, and the camera sees
// that surface only in a mirror (issue 14). A small violet-blue lamp on a black housing faces up
// into an ideal ceiling mirror (g = 0.95); the mirror sends its light down onto a grey floor and a
// fluorescent Post-it tile (scenes/materials/postit.json); the camera, under the mirror, looks up
// into it. No camera ray meets the tile or the lamp, and the lamp's front faces away from the tile.
//
// Each integrator's view of it:
// - photon mapping: camera paths pass the mirror to the tile (visible points), photons pass the
//   mirror to the tile (stored there): it converges;
// - backward: next-event estimation cannot pass the mirror, so light is found only when the
//   tile's diffuse sample hits the lamp's small image in the mirror (≈ 10⁻³ of the paths):
//   unbiased but noisy, the reference here given enough paths;
// - forward: a photon on the tile is connected to the pinhole by a straight shadow ray, and the
//   camera sees the tile only through the delta mirror, which no connection can pass (pbrt's
//   light tracer has the same blind spot): the image is black.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/embree_scene.h"
#include "render/integrator_registry.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

const char* kScene = "scenes/mirror_caustic.json";
const char kRows[] = "XYZ";

Eigen::Vector3d vec(const float v[3]) {
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d normal(const KTriangle& t) {
  return (vec(t.v1) - vec(t.v0)).cross(vec(t.v2) - vec(t.v0)).normalized();
}

// What the camera sees, found with Embree from the pinhole (independently of the integrators):
// the material met first through an image point, and the one met after one ideal reflection
// there when the first is a mirror.
class MirrorView {
 public:
  MirrorView(const Scene& scene, const Camera& camera)
      : scene_(scene),
        embree_(scene.triangles),
        camera_(camera.to_kernel()),
        camera_size_(camera) {}

  struct Seen {
    int first = -1, in_mirror = -1;  // triangle indices (scene order), -1: none
  };
  Seen through(double px, double py) const {
    Seen s;
    const float sx = static_cast<float>(2 * px / camera_size_.width - 1),
                sy = static_cast<float>(1 - 2 * py / camera_size_.height);
    KRay r{};
    for (int c = 0; c < 3; ++c) {
      r.org[c] = camera_.position[c];
      r.dir[c] = camera_.forward[c] + sx * camera_.right[c] + sy * camera_.up[c];
    }
    r.tmax = INFINITY;
    KHit h = embree_.intersect(r);
    s.first = h.prim;
    if (h.prim < 0 || !is_mirror(h.prim)) return s;
    const Eigen::Vector3d d = vec(r.dir).normalized(), n = normal(scene_.triangles[h.prim]);
    const Eigen::Vector3d p = vec(r.org) + h.t * vec(r.dir), reflected = d - 2 * d.dot(n) * n;
    for (int c = 0; c < 3; ++c) {
      r.org[c] = static_cast<float>(p[c]);
      r.dir[c] = static_cast<float>(reflected[c]);
    }
    r.tmin = 1e-4f;
    r.tmax = INFINITY;
    s.in_mirror = embree_.intersect(r).prim;
    return s;
  }
  bool is_mirror(int triangle) const {
    return scene_.material_descs[scene_.triangles[triangle].material].name == "mirror";
  }
  std::string material(int triangle) const {
    return triangle < 0 ? "" : scene_.material_descs[scene_.triangles[triangle].material].name;
  }

 private:
  const Scene& scene_;
  EmbreeScene embree_;
  KCamera camera_;
  Camera camera_size_;
};

// The pixels that see the tile's top face in the mirror through their centre and through the
// eight points one pixel away (clear of the tile's edges).
std::vector<size_t> tile_in_mirror(const Scene& scene, const Camera& camera) {
  MirrorView view(scene, camera);
  std::vector<size_t> pixels;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1 && inside; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx) {
          const MirrorView::Seen s = view.through(x + 0.5 + dx, y + 0.5 + dy);
          inside = view.is_mirror(s.first) && view.material(s.in_mirror) == "postit" &&
                   normal(scene.triangles[s.in_mirror]).y() > 0.99;
        }
      if (inside) pixels.push_back(static_cast<size_t>(y) * camera.width + x);
    }
  return pixels;
}

// The test's camera: the scene's, zoomed onto the tile's image in the mirror (fov 40° -> 12°,
// 32 × 32), so every path backward spends counts in the region compared.
Camera zoomed_camera(const Scene& scene) {
  Camera cam = scene.camera;
  cam.fov_deg = 12;
  cam.width = cam.height = 32;
  return cam;
}

TEST(MirrorCaustic, TileAndLampAreSeenAndLitOnlyThroughTheMirror) {
  const Scene scene = load_scene(source_path(kScene));
  ASSERT_TRUE(scene.fluorescent());
  MirrorView view(scene, scene.camera);
  int in_mirror = 0, tile = 0;
  // 4 × 4 rays per pixel: the camera meets nothing but the mirror (or nothing at all).
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x)
      for (int j = 0; j < 16; ++j) {
        const MirrorView::Seen s = view.through(x + (j % 4 + 0.5) / 4, y + (j / 4 + 0.5) / 4);
        ASSERT_TRUE(s.first < 0 || view.is_mirror(s.first))
            << "pixel " << x << "," << y << " sees " << view.material(s.first) << " directly";
        if (s.first < 0) continue;
        ++in_mirror;
        if (view.material(s.in_mirror) == "postit") ++tile;
        ASSERT_TRUE(s.in_mirror < 0 || scene.triangles[s.in_mirror].emitter < 0)
            << "pixel " << x << "," << y << " sees the lamp in the mirror";
      }
  EXPECT_EQ(in_mirror, 16 * scene.camera.width * scene.camera.height);
  EXPECT_GT(tile, 16 * 400);
  // The lamp's front (the side it emits from) faces away from every corner of the tile: no light
  // reaches the tile from the lamp without a bounce.
  int lamp_triangles = 0;
  for (const KTriangle& lamp : scene.triangles) {
    if (lamp.emitter < 0) continue;
    ++lamp_triangles;
    for (const KTriangle& t : scene.triangles) {
      if (scene.material_descs[t.material].name != "postit") continue;
      for (const float* v : {t.v0, t.v1, t.v2})
        EXPECT_LT(normal(lamp).dot(vec(v) - vec(lamp.v0)), 0);
    }
  }
  EXPECT_EQ(lamp_triangles, 2);
  const Camera cam = zoomed_camera(scene);
  EXPECT_EQ(tile_in_mirror(scene, cam).size(), static_cast<size_t>(cam.width * cam.height));
}

// Photon mapping's mean over the tile seen in the mirror (24 passes of 2¹⁸ photons) against
// backward's (the unbiased reference: 16 passes of 512 paths per pixel, 8.4 M paths, ≈ 1 % standard
// error), per XYZ row. The tolerance: 4 standard errors of the mean per-pixel difference plus
// kBiasAllowance of backward's mean for photon mapping's bias. The gather discs (radius ≈ 0.013)
// lie well inside the smoothly lit tile, so that bias is small: against 90 s of backward (96 k
// paths per pixel) 270 passes of photon mapping are −0.27 %, −0.57 %, −0.30 % (X, Y, Z; ± 0.4 %),
// and at seeds 1–5 this test's differences lie within ±2.3 % against tolerances of 4.8–5.8 %. It
// catches what matters here: without the tile's fluorescence (Post-it under this violet-blue lamp)
// the rows fall by 14 %, 28 %, 15 %, and twice the light is +96 %; both were checked by mutation
// (the photon render alone given the lamp at twice its scale, or the Post-it without its
// fluorescent part) and failed every row.
constexpr double kBiasAllowance = 0.02;

// vcm there (the view is caustic-lit: it merges all light at the tile, 2 camera paths and 32 light
// subpaths a pixel) is held to the same tolerance after 150 iterations.
TEST(MirrorCaustic, PhotonMappingAndVcmMatchBackwardOnTheTileSeenInTheMirror) {
  const std::string path = source_path(kScene);
  const Scene scene = load_scene(path);
  const Camera cam = zoomed_camera(scene);
  const std::vector<size_t> region = tile_in_mirror(scene, cam);
  ASSERT_EQ(region.size(), static_cast<size_t>(cam.width * cam.height));

  RenderSettings s;
  s.camera = cam;
  s.spectral = false;
  s.integrator = "backward";
  s.passes = 16;
  s.integrator_settings.spp = 512;
  const RenderResult backward = render_scene(path, s);
  EXPECT_EQ(backward.rejected, 0);
  const BinStats b = pixel_statistics(backward.image, false, region);
  for (const char* integrator : {"photon", "vcm"}) {
    s.integrator = integrator;
    s.integrator_settings.spp = 0;
    s.passes = s.integrator == "photon" ? 24 : 150;
    s.integrator_settings.photons = s.integrator == "photon" ? 1 << 18 : 0;
    const RenderResult r = render_scene(path, s);
    EXPECT_EQ(r.rejected, 0) << integrator;

    // The difference's standard error from the per-pixel differences: the tile's shading (it is
    // lit more on the lamp's side) cancels, leaving the two estimators' noise.
    const BinStats p = pixel_statistics(r.image, false, region);
    const BinStats d = difference_statistics(r.image, backward.image, false, region);
    for (int k = 0; k < 3; ++k) {
      const double tolerance = 4 * d.standard_error[k] + kBiasAllowance * b.mean[k];
      std::printf(
          "  %s, row %c: %.5f, backward %.5f, %s/backward - 1 = %+.2f %% ± %.2f %% "
          "(tolerance %.2f %%)\n",
          integrator, kRows[k], p.mean[k], b.mean[k], integrator, 100 * d.mean[k] / b.mean[k],
          100 * d.standard_error[k] / b.mean[k], 100 * tolerance / b.mean[k]);
      EXPECT_GT(b.mean[k], 0.05) << "row " << kRows[k] << ": the tile is lit";
      EXPECT_LT(tolerance, 0.07 * b.mean[k]) << integrator << ", row " << kRows[k] << ": too noisy";
      EXPECT_LT(std::abs(d.mean[k]), tolerance) << integrator << ", row " << kRows[k];
    }
  }
}

// Forward (light tracing) connects each photon's hit to the pinhole by a straight ray; here the
// camera sees nothing but the ideal mirror, which no connection passes and which takes no splat
// itself (a delta lobe), and the lamp is out of its view: not one splat lands, so the image —
// the tile's region in the mirror included — is black, whatever the photon count.
TEST(MirrorCaustic, ForwardCannotSeeTheTileThroughTheMirror) {
  const std::string path = source_path(kScene);
  const Scene scene = load_scene(path);
  const std::vector<size_t> region = tile_in_mirror(scene, scene.camera);
  ASSERT_GT(region.size(), 400u);
  RenderSettings s;
  s.spectral = false;
  s.integrator = "forward";
  s.passes = 4;
  s.integrator_settings.photons = 1 << 18;
  const RenderResult forward = render_scene(path, s);
  EXPECT_EQ(forward.rejected, 0);
  const BinStats f = pixel_statistics(forward.image, false, region);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(f.mean[k], 0.0) << "row " << kRows[k];
  double largest = 0;
  for (float v : forward.image.xyz) largest = std::max(largest, std::abs(static_cast<double>(v)));
  EXPECT_EQ(largest, 0.0) << "the whole image is seen in the mirror";
}

}  // namespace
