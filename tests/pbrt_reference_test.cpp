// kasha's images of the six pbrt-v4 test scenes (scenes/pbrt/) against pbrt-v4's own renders of
// the same files (tests/data/pbrt-v4/, how they were made: tests/data/SOURCES.md): in every region
// of at least 100 pixels that sees one material, the mean X, Y and Z agree within 1 % — the issue's
// bound for an imported scene. Backward at 32 passes, about 5 s a scene; pbrt-v4 at 1024 samples
// per pixel. Left out, with their measured differences (docs/materials.md, docs/pbrt-import.md):
// rough coats (pbrt-v4 3–5 % brighter under a lamp or the sun: its LayeredBxDF weighs a strategy
// by the wrong density, scripts/check_pbrt_rough_coat.py). The anisotropic aluminium is in: its
// brushing follows the sphere's ∂p/∂u as pbrt-v4's does (it was +1.6 % in another frame).
#include <gtest/gtest.h>

#include "image/exr_io.h"
#include "render_support.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

struct ReferenceCase {
  std::string scene;
  std::vector<std::string> left_out;  // material names, or their ":LINE" ending
  int passes = 32;
};

void PrintTo(const ReferenceCase& c, std::ostream* os) {
  *os << c.scene;
}

bool left_out(const std::string& material, const std::vector<std::string>& list) {
  for (const std::string& m : list)
    if (material == m || (material.size() > m.size() &&
                          material.compare(material.size() - m.size(), m.size(), m) == 0))
      return true;
  return false;
}

class PbrtReference : public ::testing::TestWithParam<ReferenceCase> {};

}  // namespace

TEST_P(PbrtReference, RegionMeansMatchPbrtV4WithinOnePercent) {
  const ReferenceCase& c = GetParam();
  RenderSettings s;
  s.spectral = false;
  s.passes = c.passes;
  const RenderResult kasha = render_scene(source_path("scenes/pbrt/" + c.scene + ".pbrt"), s);
  const Image pbrt = read_exr(source_path("tests/data/pbrt-v4/" + c.scene + ".exr"));
  ASSERT_EQ(pbrt.width, kasha.image.width);
  ASSERT_EQ(pbrt.height, kasha.image.height);
  int compared = 0;
  for (const auto& [material, pixels] : primary_hit_regions(kasha.scene, kasha.scene.camera)) {
    if (pixels.size() < 100 || left_out(material, c.left_out)) continue;
    const BinStats k = pixel_statistics(kasha.image, false, pixels);
    const BinStats p = pixel_statistics(pbrt, false, pixels);
    std::printf("  %-60s kasha/pbrt-v4 - 1: X %+.2f %%, Y %+.2f %%, Z %+.2f %%\n",
                material.substr(material.rfind('/') + 1).c_str(), 100 * (k.mean[0] / p.mean[0] - 1),
                100 * (k.mean[1] / p.mean[1] - 1), 100 * (k.mean[2] / p.mean[2] - 1));
    for (int row = 0; row < 3; ++row)
      EXPECT_NEAR(k.mean[row], p.mean[row], 0.01 * p.mean[row]) << material << " row " << row;
    ++compared;
  }
  EXPECT_GE(compared, 2);  // the textured scene: its floor and card
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, PbrtReference,
    ::testing::Values(
        ReferenceCase{"cornell_box", {"lacquer"}},
        // The rough copper's glossy reflections are the noisiest region.
        ReferenceCase{"rough_metals", {}, 64}, ReferenceCase{"glass", {}},
        ReferenceCase{"textured", {"textured.pbrt:38"}}, ReferenceCase{"coated_metals", {}},
        // pbrt-v4's textures of textures, nine tiles and a sphere.
        ReferenceCase{"procedural_textures", {}, 16},
        // Its rough glass block (554 pixels, lit through its nearly smooth
        // squares) is too noisy at 64 passes: +5 % at 2 standard errors.
        ReferenceCase{"rough_textures", {"rough_textures.pbrt:46"}, 64},
        // Rough layered metals in a uniform sky, where kasha's split of the
        // layer's light keeps its energy exactly (docs/materials.md).
        ReferenceCase{"layered_metals", {}, 32},
        // Absorbing media (docs/media.md): the camera in a haze, dye in glass, an
        // ink block bounded by an interface cube (its region: "(interface)").
        ReferenceCase{"media", {}, 32},
        // A cube of fog that scatters (σs spectral, g 0.3) under a lamp: the
        // free flight's MIS over bins and next-event estimation from the fog.
        ReferenceCase{"fog", {}, 32},
        // Smoke on a grid of density (uniformgrid), turned and stretched: the
        // lattice's exact tracking against pbrt-v4's delta and ratio tracking.
        ReferenceCase{"smoke", {}, 32},
        // Smoke on a sparse grid with its own turned map (nanovdb, a zipped .nvdb
        // file, read as pbrt-v4 reads it), against pbrt-v4's render.
        ReferenceCase{"vdb_smoke", {}, 32},
        // The fog cube glowing as well (a homogeneous medium's Le and Lescale):
        // emission picked up at the camera path's collisions.
        ReferenceCase{"emitting_fog", {}, 32},
        // A uniformgrid glowing as a blackbody of its temperature grid (offset and
        // scaled) times its Lescale grid, and scattering.
        ReferenceCase{"fire_grid", {}, 32},
        // The same file's temperature grid glowing (nanovdb's temperaturename,
        // offset, scale and Lescale), read on the density's voxels.
        ReferenceCase{"vdb_fire", {}, 32},
        // A colour grid (rgbgrid): its absorption a colour per sample (a component
        // per bin: 42 in all, so 8 passes), its scattering two colours, tracked exactly.
        ReferenceCase{"rgb_grid", {}, 8},
        // The same colour grid glowing (its "Le" a colour per sample, "Lescale"):
        // σa(x)·Le(x) at the camera paths' collisions, from the point's own σa.
        ReferenceCase{"emitting_rgb_grid", {}, 8}),
    [](const auto& info) { return info.param.scene; });

// --max-depth N as pbrt-v4's maxdepth: the Cornell box with direct light alone (1) and one bounce
// more (2) against pbrt-v4's renders at those caps (tests/data/SOURCES.md), region by region as
// above, within 1 %; at these caps the image is far from the uncapped one (the walls' indirect
// light is a third of it and more), so a cap counted one off would be seen.
TEST(PbrtMaxDepth, CornellBoxRegionsMatchPbrtV4AtMaxdepth1And2) {
  const Image whole = read_exr(source_path("tests/data/pbrt-v4/cornell_box.exr"));
  for (int cap : {1, 2}) {
    RenderSettings s;
    s.spectral = false;
    s.passes = 8;
    s.integrator_settings.max_depth = cap;
    const RenderResult kasha = render_scene(source_path("scenes/pbrt/cornell_box.pbrt"), s);
    const Image pbrt = read_exr(
        source_path("tests/data/pbrt-v4/cornell_box_maxdepth" + std::to_string(cap) + ".exr"));
    ASSERT_EQ(pbrt.width, kasha.image.width);
    int compared = 0;
    for (const auto& [material, pixels] : primary_hit_regions(kasha.scene, kasha.scene.camera)) {
      if (pixels.size() < 100 || left_out(material, {"lacquer"})) continue;
      const BinStats k = pixel_statistics(kasha.image, false, pixels);
      const BinStats p = pixel_statistics(pbrt, false, pixels);
      const BinStats w = pixel_statistics(whole, false, pixels);
      std::printf("  maxdepth %d %-40s kasha/pbrt-v4 - 1: Y %+.2f %% (uncapped/capped: %.3f)\n",
                  cap, material.substr(material.rfind('/') + 1).c_str(),
                  100 * (k.mean[1] / p.mean[1] - 1), w.mean[1] / p.mean[1]);
      for (int row = 0; row < 3; ++row)
        EXPECT_NEAR(k.mean[row], p.mean[row], 0.01 * p.mean[row])
            << material << " row " << row << " maxdepth " << cap;
      ++compared;
    }
    EXPECT_GE(compared, 3) << cap;
  }
}
