#pragma once
// Rendering helpers for integrator tests: a scene with its camera moved, a render to an image,
// per-bin statistics over the pixels.
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "film/image.h"
#include "film/pass_counters.h"
#include "render/integrator_registry.h"
#include "scene/scene.h"

namespace kasha::test {

struct RenderResult {
  Scene scene;
  Image image;
  long long rejected = 0;
  PassCounters counters;                         // the film's (every pass's, added)
  std::map<std::string, size_t> device_buffers;  // the integrator's
  double work_passes = 0;                        // passes, a cut-short one counted by its fraction
  int passes = 0;
  long long samples_per_pixel = 0;  // camera paths a pixel (the film's count)
};

struct RenderSettings {
  std::string integrator = "backward";
  int passes = 4;
  bool spectral = true;
  IntegratorSettings integrator_settings;  // spp, photons, seed and the rest, by name
  IntegratorTestHooks hooks;
  // Called after every pass with the pass count and the film's image (photon: error over passes).
  std::function<void(int, const Image&)> after_pass;
  // Called after every pass too: rendering stops early once it returns true.
  std::function<bool(int, const Image&)> until;
  std::optional<Camera> camera;     // replaces the scene's camera
  std::optional<GridRequest> grid;  // replaces the scene's wavelength grid
  PassControl control;              // bounds every pass (deadline, progress)
};

RenderResult render_scene(const std::string& path, const RenderSettings& settings);

struct BinStats {
  std::vector<double> mean, standard_error;  // over pixels, per bin (or per XYZ row)
};
// Per spectral bin (spectral image) or per XYZ row; pixels are independent estimates.
BinStats pixel_statistics(const Image& image, bool spectral,
                          const std::vector<size_t>& pixels = {});

// Per row, the mean over pixels of the difference a − b and its standard error: the images'
// structure cancels, leaving the two estimators' noise (pixels are independent).
BinStats difference_statistics(const Image& a, const Image& b, bool spectral,
                               const std::vector<size_t>& pixels = {});

// Every bin of the image mean against `truth`: within `tolerance` relative and, for an unbiased
// estimator, within 4 standard errors (pixels are independent estimates); bins with next to no
// light must stay as dark.
void expect_bins_match(const RenderResult& r, const std::vector<double>& truth, double tolerance,
                       const std::string& label, bool unbiased = true);

// The scene at `path` with `integrator` (64 samples a pixel or 2^17 photons, 4 passes): its first
// emitter's radiance times `transmittance` per bin, within `tolerance` (expect_bins_match,
// consistent estimators); prints the largest bin's difference.
void expect_emitter_seen_through(const std::string& path, const std::string& integrator,
                                 const std::vector<double>& transmittance, double tolerance,
                                 const std::string& label);

// The furnace scenes every integrator is tested in, and a test-name suffix for each.
extern const std::vector<const char*> kFurnaceScenes;
std::string furnace_test_name(const ::testing::TestParamInfo<const char*>& info);

// A scene at size × size (XYZ film) through `integrator` with `passes` passes of `photons`, and
// through backward (16 passes of 64 paths per pixel) to compare it with; the camera used too.
struct ComparedRenders {
  RenderResult tested, backward;
  Camera camera;
};
ComparedRenders render_against_backward(const std::string& scene, const std::string& integrator,
                                        int passes, long long photons, int size = 48);

// Pixels grouped by what their centre sees first: the material's name, or "lamp" for an emitter
// (found with Embree, independently of the integrators).
std::map<std::string, std::vector<size_t>> primary_hit_regions(const Scene& scene,
                                                               const Camera& camera);

}  // namespace kasha::test
