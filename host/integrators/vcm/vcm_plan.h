#pragma once
// What vcm and its modes decide before their kernels are built: the counts of an iteration —
// light subpaths and camera paths a pixel, SmallVCM's defaults measured here — and, from camera
// rays on the host (Embree), where camera paths merge, whether the view is caustic-lit and so
// what --merges auto means, and the pixels whose seen light has an edge.
#include <cstddef>
#include <vector>

#include "integrators/vcm/merging_distance.h"
#include "render/integrator_registry.h"
#include "render/render_settings.h"

namespace kasha {

enum class VcmMode { vcm, bpt, ppm };

// Light subpaths per iteration unless --photons says (default_light_paths): one a pixel in vcm
// and bpt, as SmallVCM (a pixel's camera paths connect to their own; with fewer than pixels ·
// spp, sample j of pixel p takes (p · spp + j) mod their count). More mostly lengthen the light
// pass: on the 32² furnaces, 2^14 of them (16 a pixel) left bpt 1.0–1.5 × backward's RMSE at 8 s,
// one a pixel 0.65–0.8 ×. ppm, merges alone, takes direct light from them too: at least this many.
constexpr size_t kLeastPhotonMappingPaths = 1 << 16;
// Camera paths a pixel per iteration unless --spp says: several share an iteration's light pass
// in vcm and bpt (measured: vcm's RMSE after 20 s on the Cornell box 0.00081 with four against
// 0.00097 with one, bpt's 0.00074 against 0.00084). Eight where no light bounces off a mirror,
// glass or a smooth coat — vcm is bpt there, and its light subpaths serve only connections and
// light tracing (bpt's RMSE after 12 s, 8 against 4: the Cornell box −11 %, the light booth
// −13 %, a million triangles −6 %); four where caustics are, whose merges and light tracing need
// fresh photons more than more camera paths (the mirror caustic +28 % with eight). ppm, whose
// estimate is all merges with the one photon map, gains nothing from more.
constexpr int kDefaultCameraPaths = 8;
constexpr int kCausticCameraPaths = 4;
constexpr int kDefaultPhotonMappingCameraPaths = 1;

// A caustic-lit view: the scene has delta surfaces and most merging vertices see no lamp
// (`unlit`, merging_distance.h), so what the camera sees is lit by caustics and the light they
// bring on, which merges and light tracing alone reach. There vcm runs as photon mapping does —
// --merges auto merges all light at the first vertex (`first`: next to a wall, the light the
// wall throws on the floor comes from connections alone under `caustic`, whose 1/d² near the
// corner leaves it short at 20 s: 0.29 against 0.35) — and with light subpaths for merges before
// camera paths: 2 camera paths a pixel unless --spp says, and 32 light subpaths a pixel whatever
// --spp says (capped at 2^31 − 1). bpt, which does not merge, gains nothing from more
// (the mirror caustic +7 % with 4 a pixel). Measured on the mirror caustic (vcm --merges first,
// RMSE after 20 s against the mean of 120-s photon-mapping and 300-s vcm renders): 4 camera paths
// and 4 light subpaths a pixel 0.0139, 4 and 16 0.0104, 4 and 32 0.0097, 4 and 64 0.0095, 2 and
// 32 0.0092, 2 and 64 0.0093, 1 and 32 0.0104; photon mapping 0.0098. The counts go with `first`:
// an explicit --merges caustic or every keeps those of other views. Elsewhere more light subpaths
// lengthen the light pass: the mirror furnace, lit directly everywhere, +9 % with 4 a pixel and +23
// % with 16.
constexpr double kMostlyUnlit = 0.5;
constexpr int kCausticLitCameraPaths = 2;
constexpr size_t kCausticLitLightPaths = 32;

// A scene with scattering media: 8 light subpaths a pixel in vcm (unless caustic-lit), whose
// collisions' light tracing and 3-D merges reach the light in the medium that camera paths find
// only by next-event estimation. RMSE after 20 s on scenes/volumetric_caustic.json against a
// 1500-s bpt render (4 camera paths a pixel): 1 light subpath a pixel 0.00063, 2 0.00052, 4
// 0.00050, 8 0.00047, 16 0.00045, 32 0.00045 (with 2 camera paths: 16 0.00044, 32 0.00056);
// pbrt-v4's fog cube (scenes/pbrt/fog.pbrt, 10 s against pbrt-v4's volpath image): 1 a pixel
// 0.0101, 8 0.0081. bpt gains less (it does not merge) and keeps one.
constexpr size_t kScatteringLightPaths = 8;

// Light subpaths an iteration and camera paths a pixel unless --photons and --spp say.
size_t default_light_paths(VcmMode m, size_t pixels, bool caustic_lit, bool scattering);
int default_camera_paths(VcmMode m, const Scene& scene, bool caustic_lit);

// What vcm takes from camera rays on the host (Embree) before its kernels are built: where
// camera paths merge, whether the view is caustic-lit, what merges, and the pixels where the
// light seen through delta bounces alone has an edge (seen_light.h).
struct VcmPlan {
  MergingVertices merging;
  bool caustic_lit = false;  // a caustic-lit view merging all light at the first vertex
  Merges merges;             // --merges, `auto` resolved: caustic, first or every
  std::vector<int> seen;     // per pixel: 1 where that light has an edge
};

VcmPlan plan_for(VcmMode m, const IntegratorSetup& s);

}  // namespace kasha
