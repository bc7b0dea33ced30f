// Textures (docs/textures.md) against ground truth computed here: a floor under a constant
// infinite light of radiance L (a convex floor sees all of it: its radiance is ρ(x)·L exactly)
// whose passive reflectance 0.8 is multiplied by
// - a checkerboard of two spectra (0.9, and an RGB colour), 6 × 6 squares over the floor's UVs:
//   the rendered radiance matches the checker computed at every point, in every integrator (the
//   analytic mean of each pixel, so also the image's mean);
// - an 8 × 4 PNG, bilinear, repeated twice each way with an offset: the truth blends the four
//   texels' spectra (the image as kasha reads it, RGB → spectrum by the table) at each point;
// and a fluorescence texture: a checkerboard of concentrations 1 and 0 on a fluorescent floor,
// whose squares match the untextured fluorescent material and the same material without its
// fluorescent part (rendered separately), within 4 standard errors of the difference.
#include <gtest/gtest.h>

#include <cmath>

#include "analytic_floor.h"
#include "color/color_space.h"
#include "image/png_preview.h"
#include "image/rgb_image.h"
#include "render_support.h"
#include "spectrum/rgb_spectrum.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
using Eigen::Vector3d;

namespace {

constexpr double kL = 0.7;  // the infinite light's radiance
const char* const kSky = R"({"type": "infinite", "radiance": 0.7})";

// The floor's texture coordinates at x: (0, 0) at the corner (−2, −2), (1, 1) at (2, 2).
Eigen::Vector2d floor_uv(const Vector3d& x) {
  return {(x.x() + 2) / 4, (x.y() + 2) / 4};
}

TEST(Texture, ACheckerboardMatchesItsAnalyticValueEverywhere) {
  const std::string textures = R"("textures": {"check": {"type": "checkerboard", "even": 0.9,
      "odd": {"rgb": [0.2, 0.5, 0.8]}, "uscale": 6, "vscale": 6}})";
  const std::string floor =
      R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "check"}})";
  const std::string scene = floor_scene("checker", floor, kSky, textures);
  const std::array<double, 3> odd_rgb = {0.2, 0.5, 0.8};
  RgbReflectanceSpectrum odd(odd_rgb);
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    Eigen::Vector2d uv = floor_uv(x);
    bool is_odd = (int(std::floor(6 * uv.x())) + int(std::floor(6 * uv.y()))) % 2 != 0;
    double t = is_odd ? odd.integral(sc.grid.lo(i), sc.grid.hi(i)) / sc.grid.bin_nm : 0.9;
    return 0.8 * t * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "photon", radiance, 16, 1 << 14, 1);
  expect_floor(scene, "forward", radiance, 0, 1 << 18, 2);
}

TEST(Texture, AnImageIsLookedUpBilinearlyWithWrapAndOffset) {
  // An 8 × 4 image of distinct colours, as kasha reads it back.
  Image img;
  img.width = 8;
  img.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      Vec3d rgb = {0.1 + 0.1 * x, 0.8 - 0.15 * y, 0.3 + 0.3 * ((x + y) % 2)};
      Vec3d xyz = linear_srgb_to_xyz(rgb);
      for (double v : xyz) img.xyz.push_back(static_cast<float>(v));
    }
  const std::string png = (scratch_dir() / "print.png").string();
  write_png_preview(png, img, 1.0);
  const RgbImage texels = read_rgb_image(png);
  const std::string textures = R"("textures": {"print": {"type": "image", "file": ")" + png +
                               R"(", "uscale": 2, "vscale": 2, "udelta": 0.1, "vdelta": -0.3}})";
  const std::string floor =
      R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "print"}})";
  const std::string scene = floor_scene("image", floor, kSky, textures);
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    Eigen::Vector2d uv = floor_uv(x);
    double s = 2 * uv.x() + 0.1, t = 2 * uv.y() - 0.3;
    // pbrt-v4's lookup: rows from the top, t up; bilinear between texel centres; repeat.
    double fx = s * texels.width - 0.5, fy = (1 - t) * texels.height - 0.5;
    int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    double wx = fx - x0, wy = fy - y0, v = 0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        int tx = ((x0 + dx) % texels.width + texels.width) % texels.width;
        int ty = ((y0 + dy) % texels.height + texels.height) % texels.height;
        const float* p = texels.at(tx, ty);
        double w = (dx ? wx : 1 - wx) * (dy ? wy : 1 - wy);
        v += w * sigmoid_spectrum(rgb_sigmoid({p[0], p[1], p[2]}), sc.grid.center(i));
      }
    return 0.8 * v * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "forward", radiance, 0, 1 << 18, 2);
}

// pbrt-v4's invert of the scaled texels (1 − 0.5·texel) and its octahedralsphere wrap
// (RemapPixelCoords: across a vertical edge mirrored in x and in y about the middle, across a
// horizontal edge likewise), on lookups half beyond the left edge of an image that brightens
// to the right (clamping there would give its darkest column).
TEST(Texture, AnInvertedImageWrapsAsPbrtV4sOctahedralSphere) {
  Image img;
  img.width = 4;
  img.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      Vec3d rgb = {0.05 + 0.3 * x, 0.9 - 0.2 * y, 0.2 + 0.25 * x};
      Vec3d xyz = linear_srgb_to_xyz(rgb);
      for (double v : xyz) img.xyz.push_back(static_cast<float>(v));
    }
  const std::string png = (scratch_dir() / "octahedral.png").string();
  write_png_preview(png, img, 1.0);
  const RgbImage texels = read_rgb_image(png);
  const std::string textures = R"("textures": {"print": {"type": "image", "file": ")" + png +
                               R"(", "wrap": "octahedral_sphere", "invert": true, "scale": 0.5,
      "udelta": -0.5}})";
  const std::string floor =
      R"({"passive": {"reflectance": 0.8}, "textures": {"reflectance": "print"}})";
  const std::string scene = floor_scene("octahedral", floor, kSky, textures);
  auto remap = [&](int x, int y) {
    const int w = texels.width, h = texels.height;
    if (x < 0 || x >= w) x = x < 0 ? -x : 2 * w - 1 - x, y = h - 1 - y;
    if (y < 0 || y >= h) y = y < 0 ? -y : 2 * h - 1 - y, x = w - 1 - x;
    return std::pair<int, int>(x, y);
  };
  auto radiance = [&](const Scene& sc, const Vector3d& x, int i) {
    Eigen::Vector2d uv = floor_uv(x);
    double s = uv.x() - 0.5, t = uv.y();
    double fx = s * texels.width - 0.5, fy = (1 - t) * texels.height - 0.5;
    int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    double wx = fx - x0, wy = fy - y0, v = 0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        auto [tx, ty] = remap(x0 + dx, y0 + dy);
        tx = std::clamp(tx, 0, texels.width - 1);
        ty = std::clamp(ty, 0, texels.height - 1);
        const float* p = texels.at(tx, ty);
        std::array<double, 3> inv;
        for (int k = 0; k < 3; ++k) inv[k] = std::max(0.0, 1 - 0.5 * p[k]);
        double w = (dx ? wx : 1 - wx) * (dy ? wy : 1 - wy);
        v += w * sigmoid_spectrum(rgb_sigmoid(inv), sc.grid.center(i));
      }
    return 0.8 * v * kL;
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
}

// A fluorescent floor under UV and blue light: its excitation at 380–450 nm re-emitted at 550 nm.
const char* const kFluorescentFloor = R"({"passive": {"reflectance": 0.3},
    "fluorescence": {"excitation": {"nm": [360, 380, 450, 470], "value": [0, 0.5, 0.5, 0]},
                     "emission": {"gaussian_nm": 550, "fwhm_nm": 40}}})";

TEST(Texture, AFluorescenceTextureAtOneAndZeroMatchesTheMaterialWithAndWithout) {
  const std::string light =
      R"({"type": "infinite", "radiance": {"nm": [350, 480, 700], "value": [1, 1, 0.3]}})";
  const std::string textures = R"("textures": {"ink": {"type": "checkerboard", "even": 1, "odd": 0,
      "uscale": 4, "vscale": 4}})";
  std::string textured = kFluorescentFloor;
  textured.insert(textured.size() - 1, R"(, "textures": {"fluorescence": "ink"})");
  auto grid_scene = [&](const std::string& name, const std::string& floor,
                        const std::string& extra) {
    std::string path = floor_scene(name, floor, light, extra);
    return path;
  };
  RenderSettings s;
  s.passes = 2;
  s.integrator_settings.spp = 16;
  RenderResult inked = render_scene(grid_scene("inked", textured, textures), s);
  RenderResult with = render_scene(grid_scene("fluorescent", kFluorescentFloor, ""), s);
  RenderResult without =
      render_scene(grid_scene("passive", R"({"passive": {"reflectance": 0.3}})", ""), s);
  // Pixels wholly inside an even (ink) or odd (no ink) square.
  const KCamera cam = inked.scene.camera.to_kernel();
  std::vector<size_t> even, odd;
  for (int py = 0; py < kFloorSize; ++py)
    for (int px = 0; px < kFloorSize; ++px) {
      int parity = -1;
      for (int a = 0; a <= 4 && parity != -2; ++a)
        for (int b = 0; b <= 4; ++b) {
          Eigen::Vector2d uv = floor_uv(floor_point(cam, px + a / 4.0, py + b / 4.0));
          int p = (int(std::floor(4 * uv.x())) + int(std::floor(4 * uv.y()))) & 1;
          if (parity == -1) parity = p;
          if (p != parity) {
            parity = -2;
            break;
          }
        }
      if (parity == 0) even.push_back(py * kFloorSize + px);
      if (parity == 1) odd.push_back(py * kFloorSize + px);
    }
  ASSERT_GT(even.size(), 50u);
  ASSERT_GT(odd.size(), 50u);
  const size_t N = inked.scene.grid.bins;
  for (auto [pixels, reference, label] :
       {std::tuple{even, &with, "ink (concentration 1) vs the fluorescent material"},
        std::tuple{odd, &without, "no ink (0) vs the passive part alone"}}) {
    BinStats d = difference_statistics(inked.image, reference->image, true, pixels);
    BinStats t = pixel_statistics(reference->image, true, pixels);
    for (size_t i = 0; i < N; ++i)
      EXPECT_LE(std::abs(d.mean[i]), 4 * d.standard_error[i] + 1e-6 * t.mean[i])
          << label << ", bin " << i << ": " << d.mean[i] << " ± " << d.standard_error[i];
  }
  // And the ink shows: at 550 nm the inked squares are brighter than the bare ones.
  const int green = inked.scene.grid.bin_of(550);
  EXPECT_GT(pixel_statistics(inked.image, true, even).mean[green],
            1.2 * pixel_statistics(inked.image, true, odd).mean[green]);
}

// An emitter with an emission texture: seen directly its radiance is Le·t(u, v) (backward and
// photon mapping by hitting it, forward by connecting its photons' starts to the camera); and it
// lights a grey floor (next-event estimation scales each light point, photons leave with the
// texture's factor): backward and forward agree there in every 4 × 4 block within 4 standard
// errors of the difference.
TEST(Texture, AnEmissionTextureScalesTheEmittersRadianceWhereverItIsSeenOrSampled) {
  const std::string textures = R"("textures": {"pattern": {"type": "checkerboard", "even": 1.5,
      "odd": 0.25, "uscale": 3, "vscale": 2}})";
  const std::string scene = floor_scene("glowing", "{}", "", textures,
                                        R"("emission": 0.6, "emission_texture": "pattern")");
  auto radiance = [](const Scene&, const Vector3d& x, int) {
    Eigen::Vector2d uv = floor_uv(x);
    bool odd = (int(std::floor(3 * uv.x())) + int(std::floor(2 * uv.y()))) % 2 != 0;
    return 0.6 * (odd ? 0.25 : 1.5);
  };
  expect_floor(scene, "backward", radiance, 16, 0, 1);
  expect_floor(scene, "photon", radiance, 16, 1 << 14, 1);
  expect_floor(scene, "forward", radiance, 0, 1 << 18, 2);

  // The textured lamp (facing down, 0.8 above, beside the camera's view) over the grey floor.
  const std::string lit = floor_scene(
      "lit", R"({"passive": {"reflectance": 0.5}}, "black": {})", "", textures, "",
      R"({"type": "quad", "corner": [1.4, -1, 0.8], "u": [0, 2, 0], "v": [1, 0, 0], "material": "black",
          "emission": 2, "emission_texture": "pattern"})");
  RenderSettings s;
  s.passes = 4;
  s.integrator_settings.spp = 16;
  RenderResult back = render_scene(lit, s);
  s.integrator = "forward";
  s.integrator_settings.photons = 1 << 18;
  RenderResult fwd = render_scene(lit, s);
  int blocks = 0;
  for (int by = 0; by < kFloorSize / 4; ++by)
    for (int bx = 0; bx < kFloorSize / 4; ++bx) {
      std::vector<size_t> block;
      for (int y = 4 * by; y < 4 * by + 4; ++y)
        for (int x = 4 * bx; x < 4 * bx + 4; ++x) block.push_back(size_t(y) * kFloorSize + x);
      BinStats d = difference_statistics(fwd.image, back.image, true, block);
      BinStats t = pixel_statistics(back.image, true, block);
      for (size_t i = 0; i < d.mean.size(); ++i)
        if (!(std::abs(d.mean[i]) <= 4 * d.standard_error[i] + 0.002 * t.mean[i]) && ++blocks <= 5)
          ADD_FAILURE() << "block " << bx << "," << by << " bin " << i << ": forward − backward "
                        << d.mean[i] << " ± " << d.standard_error[i] << " of " << t.mean[i];
    }
  EXPECT_EQ(blocks, 0);
}

}  // namespace
