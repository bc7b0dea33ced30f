#include "render_support.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "image/exr_io.h"
#include "render/device_scene.h"
#include "render/render_job.h"
#include "study/image_regions.h"
#include "test_support.h"

namespace kasha::test {

RenderResult render_scene(const std::string& path, const RenderSettings& s) {
  static ClContext cl(0);
  RenderResult r;
  r.scene = load_scene(path, s.grid);
  if (s.camera) r.scene.camera = *s.camera;
  DeviceScene ds(cl, r.scene);
  RenderJob job(cl, r.scene, ds, s.integrator, s.integrator_settings, s.spectral, s.hooks);
  job.integrator().set_control(s.control);
  for (int p = 0; p < s.passes; ++p) {
    job.pass(p);
    if (s.after_pass) s.after_pass(p + 1, job.film().image());
    if (s.until && s.until(p + 1, job.film().image())) break;
  }
  r.image = job.film().image();
  r.counters = job.film().counters();
  r.rejected = static_cast<long long>(r.counters.rejected_samples);
  r.device_buffers = job.integrator().device_buffers();
  r.work_passes = job.film().work_passes();
  r.passes = job.film().passes();
  r.samples_per_pixel = job.film().samples_per_pixel();
  return r;
}

BinStats pixel_statistics(const Image& image, bool spectral, const std::vector<size_t>& pixels) {
  const size_t rows = spectral ? image.grid.bins : 3;
  const std::vector<float>& v = spectral ? image.spectral : image.xyz;
  std::vector<size_t> use = pixels;
  if (use.empty())
    for (size_t p = 0; p < image.pixels(); ++p) use.push_back(p);
  BinStats s;
  s.mean.assign(rows, 0.0);
  s.standard_error.assign(rows, 0.0);
  for (size_t r = 0; r < rows; ++r) {
    double sum = 0, sum2 = 0;
    for (size_t p : use) {
      double x = v[p * rows + r];
      sum += x;
      sum2 += x * x;
    }
    double n = use.size(), mean = sum / n;
    s.mean[r] = mean;
    s.standard_error[r] = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
  }
  return s;
}

BinStats difference_statistics(const Image& a, const Image& b, bool spectral,
                               const std::vector<size_t>& pixels) {
  Image d = a;
  std::vector<float>& v = spectral ? d.spectral : d.xyz;
  const std::vector<float>& w = spectral ? b.spectral : b.xyz;
  for (size_t i = 0; i < v.size(); ++i) v[i] -= w[i];
  return pixel_statistics(d, spectral, pixels);
}

void expect_bins_match(const RenderResult& r, const std::vector<double>& truth, double tolerance,
                       const std::string& label, bool unbiased) {
  BinStats s = pixel_statistics(r.image, true);
  double peak = *std::max_element(truth.begin(), truth.end());
  int checked = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    const double nm = r.scene.grid.center(static_cast<int>(i));
    if (truth[i] < 1e-3 * peak) {
      EXPECT_LT(s.mean[i], 2e-3 * peak + 4 * s.standard_error[i])
          << label << " bin " << nm << " nm";
      continue;
    }
    ++checked;
    if (unbiased) {
      EXPECT_LT(std::abs(s.mean[i] - truth[i]), 4 * s.standard_error[i] + 1e-6 * truth[i])
          << label << " bin " << nm << " nm: " << s.mean[i] << " vs " << truth[i] << " ± "
          << s.standard_error[i];
    }
    EXPECT_LT(std::abs(s.mean[i] - truth[i]), tolerance * truth[i])
        << label << " bin " << nm << " nm";
  }
  EXPECT_GT(checked, 3) << label;
  EXPECT_EQ(r.rejected, 0) << label;
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v)) << label;
}

const std::vector<const char*> kFurnaceScenes = {"furnace_passive.json", "furnace_fluorescent.json",
                                                 "furnace_uv.json", "furnace_self_absorption.json",
                                                 "furnace_mirror.json"};

std::string furnace_test_name(const ::testing::TestParamInfo<const char*>& info) {
  std::string s = info.param;  // furnace_<name>.json -> <name>
  return s.substr(8, s.size() - 13);
}

static std::string slashes_to_underscores(std::string s) {
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

ComparedRenders render_against_backward(const std::string& scene, const std::string& integrator,
                                        int passes, long long photons, int size) {
  const std::string path = source_path("scenes/" + scene);
  ComparedRenders pair;
  pair.camera = load_scene(path).camera;
  pair.camera.width = pair.camera.height = size;
  RenderSettings s;
  s.camera = pair.camera;
  s.spectral = false;
  s.integrator = integrator;
  s.passes = passes;
  s.integrator_settings.photons = photons;
  pair.tested = render_scene(path, s);
  // The reference is the same for every integrator compared on the scene (a fixed seed): rendered
  // once per build of this binary and kept beside the tests' scratch folders, keyed by the
  // binary's write time (the kernels are compiled into it, so a changed kernel renders it again).
  // Written under a temporary name and renamed, so tests running side by side never read half.
  const auto built = std::filesystem::last_write_time("/proc/self/exe").time_since_epoch().count();
  const std::filesystem::path cache = std::filesystem::path(KASHA_TEST_TMP) /
                                      "backward_references" /
                                      (std::to_string(built) + "_" + std::to_string(size) + "_" +
                                       slashes_to_underscores(scene) + ".exr");
  if (std::filesystem::exists(cache)) {
    pair.backward.scene = pair.tested.scene;
    pair.backward.image = read_exr(cache.string());
    return pair;
  }
  s.integrator = "backward";
  s.passes = 16;
  s.integrator_settings.spp = 64;
  pair.backward = render_scene(path, s);
  std::filesystem::create_directories(cache.parent_path());
  const std::string partial = cache.string() + "." + std::to_string(::getpid()) + ".part.exr";
  write_exr(partial, pair.backward.image);
  std::filesystem::rename(partial, cache);
  return pair;
}

std::map<std::string, std::vector<size_t>> primary_hit_regions(const Scene& scene,
                                                               const Camera& cam) {
  std::map<std::string, std::vector<size_t>> regions;
  for (const ShapeRegion& r : shape_regions(scene, cam)) {
    const ShapeInfo& shape = scene.shapes[r.shape];
    auto& into = regions[shape.emitter >= 0 ? "lamp" : scene.material_descs[shape.material].name];
    into.insert(into.end(), r.pixels.begin(), r.pixels.end());
  }
  for (auto& [name, pixels] : regions) std::sort(pixels.begin(), pixels.end());
  return regions;
}

void expect_emitter_seen_through(const std::string& path, const std::string& integrator,
                                 const std::vector<double>& transmittance, double tolerance,
                                 const std::string& label) {
  RenderSettings s;
  s.integrator = integrator;
  s.integrator_settings.spp = 64;
  s.integrator_settings.photons = 1 << 17;
  s.passes = 4;
  RenderResult r = render_scene(path, s);
  std::vector<double> expected = r.scene.emitters.at(0).per_bin;
  for (size_t i = 0; i < expected.size(); ++i) expected[i] *= transmittance.at(i);
  const BinStats b = pixel_statistics(r.image, true);
  double worst = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    worst = std::max(worst, std::abs(b.mean[i] / expected[i] - 1));
  std::printf("  %s: the largest bin's difference %.2f %%\n", integrator.c_str(), 100 * worst);
  expect_bins_match(r, expected, tolerance, label, false);
}

}  // namespace kasha::test
