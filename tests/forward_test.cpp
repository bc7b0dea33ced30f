// The forward integrator (light tracing): its power bookkeeping, a film that does not depend on
// how work is split, and a film that stays exact for any light: UV-only lines on an XYZ film,
// radiance from 1e-30 to 1e28, a tiny bright emitter (its furnace and agreement tests in the
// ordinary range are in integrator_*_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "kernel_harness.h"
#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Forward, PowerIsConservedInAClosedScene) {
  // Photons cut after 3 bounces: absorbed (what hits took away, roulette included) + escaped +
  // still in flight = emitted exactly. Next to nothing escapes a closed scene: a photon in about
  // 10^5 slips through the float cracks of a tessellated sphere (issue 12's ray offsets).
  RenderSettings s;
  s.integrator = "forward";
  s.passes = 2;
  s.integrator_settings.photons = 100000;
  s.integrator_settings.depth_guard = 3;
  for (const char* scene : {"furnace_fluorescent.json", "furnace_mirror.json", "furnace_uv.json"}) {
    RenderResult r = render_scene(source_path(std::string("scenes/") + scene), s);
    const double emitted = r.counters.power_emitted_w, absorbed = r.counters.power_absorbed_w,
                 escaped = r.counters.power_escaped_w, in_flight = r.counters.power_in_flight_w;
    EXPECT_NEAR(absorbed + escaped + in_flight, emitted, 1e-5 * emitted) << scene;
    EXPECT_LT(escaped, 1e-5 * emitted) << scene;
    EXPECT_GT(in_flight, 0.05 * emitted) << scene;  // the cut leaves photons in flight
    // A pass's photons carry the lights' total power.
    KernelSceneData data(r.scene);
    EXPECT_NEAR(emitted, 2 * data.total_power, 1e-4 * data.total_power) << scene;
  }
}

TEST(Forward, ImageDoesNotDependOnHowWorkIsSplit) {
  // The same photons spread over work items of 64, 7 and 1 photons: each photon's random numbers
  // depend on its index only and the fixed-point film adds exactly, so the images are identical.
  RenderSettings a;
  a.integrator = "forward";
  a.spectral = false;
  a.passes = 1;
  a.integrator_settings.photons = 40000;
  std::vector<float> reference;
  for (int per_item : {64, 7, 1}) {
    a.hooks.photons_per_item = per_item;
    RenderResult r = render_scene(source_path("scenes/furnace_fluorescent.json"), a);
    if (reference.empty()) reference = r.image.xyz;
    EXPECT_EQ(r.image.xyz, reference) << per_item << " photons per work item";
  }
}

namespace {

// A 2 × 2 × 2.5 m box enclosure of `material` (a JSON material) with `emission` on its walls (or
// none), further `shapes`, and an 8 × 8 camera inside.
std::string box_scene(const std::string& file, const std::string& material,
                      const std::string& emission, const std::string& shapes = "",
                      const std::string& camera = R"("position": [0.2, 0.1, -0.6],
                                                       "look_at": [-0.5, -0.2, 1], "fov_deg": 60)") {
  return write_file(file, R"({"kasha_scene": 1,
    "camera": {)" + camera + R"(, "width": 8, "height": 8},
    "materials": {"wall": )" + material +
                              R"(},
    "shapes": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1.5], "material": "wall",
                "inward": true)" +
                              (emission.empty() ? "" : R"(, "emission": )" + emission) + "}" +
                              shapes + "]}");
}

// Excited from 240 to 370 nm (less towards 370 nm), emitting around 500 nm (an optical brightener).
const char* kBrightener = R"({"passive": {"reflectance": 0.3},
    "fluorescence": {"excitation": {"nm": [240, 370, 380], "value": [0.6, 0.4, 0]},
                     "emission": {"gaussian_nm": 500, "fwhm_nm": 60}}})";
// The fluorescent furnace's material (scenes/furnace_fluorescent.json).
const char* kBrightened = R"({"passive": {"reflectance": {"nm": [380, 480, 560, 780],
                                                         "value": [0.1, 0.3, 0.55, 0.6]}},
    "fluorescence": {"excitation": {"gaussian_nm": 430, "fwhm_nm": 70, "scale": 0.35},
                     "emission": {"gaussian_nm": 530, "fwhm_nm": 50}}})";

struct FilmCase {
  std::string name;
  std::function<std::string()> scene;  // writes the scene, returns its path
  bool furnace;                        // the truth: the analytic furnace, else backward
  bool spectral;                       // spectral film, else XYZ
};

void PrintTo(const FilmCase& c, std::ostream* os) {
  *os << c.name;
}

std::vector<FilmCase> film_cases() {
  std::vector<std::pair<std::string, std::pair<std::function<std::string()>, bool>>> scenes = {
      // Light only below 360 nm, where the colour-matching functions are zero: on an XYZ film
      // the emitters are black, and all the image comes from fluorescence.
      {"uv340", {[] { return box_scene("uv340.json", kBrightener, R"({"line_nm": 340})"); }, true}},
      {"uv250", {[] { return box_scene("uv250.json", kBrightener, R"({"line_nm": 250})"); }, true}},
      // scenes/furnace_fluorescent.json's light × 1e-30 and × 1e28.
      {"dim",
       {[] {
          return box_scene("dim.json", kBrightened,
                           R"({"csv": ")" + source_path("scenes/data/CIE_D65_300_780.csv") +
                               R"(", "scale": 1e-32})");
        },
        true}},
      {"bright",
       {[] {
          return box_scene("bright.json", kBrightened,
                           R"({"csv": ")" + source_path("scenes/data/CIE_D65_300_780.csv") +
                               R"(", "scale": 1e26})");
        },
        true}},
      // A lamp of 1e-8 of the scene's area under the ceiling, with an ordinary power (~100 W,
      // radiance ~3e5 per nm), out of the camera's view (backward could not see it directly).
      {"tiny",
       {[] {
          return box_scene("tiny.json", kBrightened, "",
                           R"(,
            {"type": "quad", "corner": [-0.00026, 0.999, 0.25], "u": [0.00053, 0, 0],
             "v": [0, 0, 0.00053], "material": "wall", "emission": {"csv": ")" +
                               source_path("scenes/data/CIE_D65_300_780.csv") +
                               R"(", "scale": 3000}})",
                           R"("position": [0, 0.4, -0.9], "look_at": [0, -1, 0.8], "fov_deg": 50)");
        },
        false}}};
  std::vector<FilmCase> cases;
  for (const auto& [name, scene] : scenes)
    for (bool spectral : {false, true})
      cases.push_back(
          {name + (spectral ? "_spectral" : "_xyz"), scene.first, scene.second, spectral});
  return cases;
}

// The image mean's relative standard error, worst over rows with light (above 1e-3 of the peak).
double worst_error_bar(const Image& image, bool spectral) {
  BinStats s = pixel_statistics(image, spectral);
  double peak = *std::max_element(s.mean.begin(), s.mean.end()), worst = 0;
  for (size_t i = 0; i < s.mean.size(); ++i)
    if (s.mean[i] >= 1e-3 * peak) worst = std::max(worst, s.standard_error[i] / s.mean[i]);
  return worst;
}

class ForwardFilmRange : public ::testing::TestWithParam<FilmCase> {};

TEST_P(ForwardFilmRange, MatchesTheTruthWithoutRejectedSamples) {
  const FilmCase& c = GetParam();
  const std::string path = c.scene();
  RenderSettings s;
  s.integrator = "forward";
  s.spectral = c.spectral;
  s.integrator_settings.photons = 1 << 14;
  // A furnace's image is uniform: passes until the mean's error bar is 0.5 % in every lit row, so
  // 3 % is ~6 of them. Against backward the image has structure: a fixed budget.
  s.passes = c.furnace ? 64 : 16;
  int passes = s.passes;
  if (c.furnace)
    s.until = [&](int pass, const Image& img) {
      passes = pass;
      return pass >= 4 && worst_error_bar(img, c.spectral) < 0.005;
    };
  RenderResult r = render_scene(path, s);

  // Truth per row (XYZ or bin) and the standard error of (forward − truth).
  std::vector<double> truth, error_bar, difference;
  BinStats t = pixel_statistics(r.image, c.spectral);
  if (c.furnace) {
    Furnace f = analyze_furnace(r.scene);
    ASSERT_TRUE(f.qualifies) << f.why_not;
    Image img = furnace_image(r.scene, f.radiance, c.spectral);
    const std::vector<float>& v = c.spectral ? img.spectral : img.xyz;
    truth.assign(v.begin(), v.begin() + t.mean.size());
    error_bar = t.standard_error;
    for (size_t i = 0; i < truth.size(); ++i) difference.push_back(t.mean[i] - truth[i]);
  } else {
    RenderSettings b = s;
    b.integrator = "backward";
    b.until = nullptr;
    b.passes = 4;
    b.integrator_settings.spp = 1024;
    RenderResult ref = render_scene(path, b);
    EXPECT_EQ(ref.rejected, 0);
    BinStats d = difference_statistics(r.image, ref.image, c.spectral);
    for (size_t i = 0; i < t.mean.size(); ++i) truth.push_back(t.mean[i] - d.mean[i]);
    error_bar = d.standard_error;
    difference = d.mean;
  }
  const double peak = *std::max_element(truth.begin(), truth.end());
  ASSERT_GT(peak, 0);
  int checked = 0;
  double worst = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] < 1e-3 * peak) {
      EXPECT_LT(std::abs(difference[i]), 2e-3 * peak + 4 * error_bar[i]) << c.name << " row " << i;
      continue;
    }
    ++checked;
    worst = std::max(worst, std::abs(difference[i]) / error_bar[i]);
    EXPECT_LT(std::abs(difference[i]), 4 * error_bar[i])
        << c.name << " row " << i << ": " << truth[i] + difference[i] << " vs " << truth[i] << " ± "
        << error_bar[i];
    EXPECT_LT(std::abs(difference[i]), 0.03 * truth[i]) << c.name << " row " << i;
  }
  EXPECT_GE(checked, 3);
  const size_t y = c.spectral ? std::max_element(truth.begin(), truth.end()) - truth.begin() : 1;
  std::printf("  %s: %d passes, row %zu %.6g vs %s %.6g (%+.3f %%, σ %.3f %%), worst |d|/σ %.2f\n",
              c.name.c_str(), passes, y, truth[y] + difference[y],
              c.furnace ? "furnace" : "backward", truth[y], 100 * difference[y] / truth[y],
              100 * error_bar[y] / truth[y], worst);
  EXPECT_EQ(r.rejected, 0) << c.name;
  for (float v : r.image.xyz) ASSERT_TRUE(std::isfinite(v)) << c.name;
  for (float v : r.image.spectral) ASSERT_TRUE(std::isfinite(v)) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Extremes, ForwardFilmRange, ::testing::ValuesIn(film_cases()),
                         [](const auto& info) { return info.param.name; });

// A film cell's words (lo, hi) after `values` are splatted into it by one work item each, and the
// count of rejected ones.
struct Cell {
  uint64_t lo = 0, hi = 0;
  int rejected = 0;
};
Cell splat_all(const std::vector<float>& values, int shift) {
  static const char* source = R"(#include "film/film_splat.h"
    __kernel void splat(__global const float* values, int shift, __global ulong* cell,
                        __global int* rejected, int clear) {
      if (clear) {
        cell[0] = cell[1] = 0;
        *rejected = 0;
        return;
      }
      int r = 0;
      splat_fixed(cell, values[get_global_id(0)], shift, &r);
      if (r) atomic_add(rejected, r);
    })";
  TestKernel k(source, "film_sum_test", "splat");
  k.input(0, values);
  k.scalar(1, shift);
  k.output(2, 4);  // two ulong words
  k.output(3, 1);
  k.scalar(4, 1);
  k.run(1);
  k.scalar(4, 0);
  k.run(values.size());
  std::vector<float> words = k.read(2), rejected = k.read(3);
  Cell c;
  std::memcpy(&c.lo, &words[0], 8);
  std::memcpy(&c.hi, &words[2], 8);
  std::memcpy(&c.rejected, &rejected[0], 4);
  return c;
}

}  // namespace

TEST(ForwardFilm, SumIsExactWithCarriesAndRejectsWhatItCannotHold) {
  // Values from 2^-30 to 2^30 film units · 2^40: the low word wraps again and again, and small
  // values round. The 128-bit sum must equal the exact sum of the rounded splats, in any order.
  __extension__ typedef unsigned __int128 u128;
  const int shift = 40;
  std::vector<float> values;
  u128 exact = 0;
  uint32_t state = 12345;
  for (int i = 0; i < 20000; ++i) {
    state = state * 1664525u + 1013904223u;
    float v =
        std::ldexp(static_cast<float>(state >> 8) / (1 << 24), static_cast<int>(state % 61) - 30);
    values.push_back(v);
    exact += static_cast<u128>(std::nearbyint(std::ldexp(v, shift)));
  }
  ASSERT_GT(exact >> 64, 1000u);  // many carries
  Cell a = splat_all(values, shift);
  std::reverse(values.begin(), values.end());
  Cell b = splat_all(values, shift);
  EXPECT_EQ(a.lo, static_cast<uint64_t>(exact));
  EXPECT_EQ(a.hi, static_cast<uint64_t>(exact >> 64));
  EXPECT_EQ(b.lo, a.lo);
  EXPECT_EQ(b.hi, a.hi);
  EXPECT_EQ(a.rejected, 0);

  // Negative, non-finite and ≥ 2^127 units are rejected, and add nothing.
  Cell r = splat_all({-1.0f, NAN, INFINITY, std::ldexp(1.0f, 127 - shift), 1.0f}, shift);
  EXPECT_EQ(r.rejected, 4);
  EXPECT_EQ(r.lo, uint64_t(1) << shift);
  EXPECT_EQ(r.hi, 0u);
}

TEST(ForwardFilm, SpectralImageDoesNotDependOnHowWorkIsSplit) {
  // As above, on a spectral film lit by a UV line, and a tiny lamp: bit for bit.
  for (const std::string& scene : {box_scene("split_uv.json", kBrightener, R"({"line_nm": 250})"),
                                   box_scene("split_tiny.json", kBrightened, "", R"(,
            {"type": "quad", "corner": [0, 0.999, 0.25], "u": [0.0005, 0, 0],
             "v": [0, 0, 0.0005], "material": "wall", "emission": {"line_nm": 550, "scale": 1e7}})")}) {
    RenderSettings a;
    a.integrator = "forward";
    a.spectral = true;
    a.passes = 1;
    a.integrator_settings.photons = 20000;
    std::vector<float> reference;
    for (int per_item : {64, 7, 1}) {
      a.hooks.photons_per_item = per_item;
      RenderResult r = render_scene(scene, a);
      EXPECT_EQ(r.rejected, 0);
      if (reference.empty()) reference = r.image.spectral;
      EXPECT_EQ(r.image.spectral, reference) << scene << ": " << per_item << " photons per item";
    }
  }
}
