// `kasha converge`: rates of convergence on a furnace match theory, the study writes what it
// promises, and bad arguments give one clear line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "study/convergence_log.h"
#include "study/convergence_study.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {
// Least-squares slope of log error over log passes, after the first 5 % of the passes: each pass
// is the same work, so this is the rate against run time without timing anything.
double slope_over_passes(const std::vector<LogRow>& log, bool relative) {
  std::vector<double> x, y;
  for (const LogRow& row : log)
    if (row.pass > 0.05 * log.size()) {
      x.push_back(std::log(row.pass));
      y.push_back(std::log(relative ? row.relmse : row.rmse));
    }
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / x.size(), my += y[i] / y.size();
  for (size_t i = 0; i < x.size(); ++i)
    sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxy / sxx;
}
}  // namespace

TEST(Converge, FurnaceSlopesMatchTheory) {
  StudyOptions o;
  o.passes = 64;
  o.reference = "furnace";
  o.settings.sampler =
      Sampler::independent;  // the theory is Monte Carlo's; Sobol points may do better
  o.settings.spp = 4;
  o.settings.photons = 1 << 14;
  o.out_dir = (scratch_dir() / "study").string();
  o.show_progress = false;
  StudyResult r = run_convergence_study(source_path("scenes/furnace_fluorescent.json"), o);
  ASSERT_EQ(r.summaries.size(), o.integrators.size());
  for (const IntegratorSummary& s : r.summaries) {
    bool unbiased = IntegratorRegistry::find(s.integrator).traits.unbiased;
    // Progressive photon mapping's variance falls as passes^−α (Knaus & Zwicker 2011); in the
    // furnace its bias is nil (uniform density, edges corrected), so its RMSE goes as −α/2.
    double theory = unbiased ? -0.5 : -o.settings.alpha / 2;
    std::vector<LogRow> log = read_convergence_log(o.out_dir + "/log_" + s.integrator + "_1.csv");
    ASSERT_EQ(log.size(), 64u);
    double slope = slope_over_passes(log, false), slope_rel = slope_over_passes(log, true);
    if (s.integrator == "vcm") {
      // Connections (−1/2) and merges (−α/2) under one weight: between the two, nearer the
      // technique that dominates (in a furnace, the connections: measured −0.51).
      EXPECT_LT(slope, -o.settings.alpha / 2 + 0.1) << s.integrator;
      EXPECT_GT(slope, -0.5 - 0.1) << s.integrator;
      EXPECT_LT(slope_rel, -o.settings.alpha + 0.2) << s.integrator;
      EXPECT_GT(slope_rel, -1.0 - 0.2) << s.integrator;
    } else if (s.integrator == "ppm") {
      // Merges: what the edge correction leaves of the bias at the box's edges and corners falls
      // with the radius, as passes^((α−1)/2) (−0.1), while their variance falls as −α/2 (−0.4).
      // Each camera path's radius is a pixel's footprint at its distance (0.06–0.09 here, 32²
      // pixels): measured −0.412 with the correction, −0.27 without it.
      EXPECT_LT(slope, -(1 - o.settings.alpha) / 2 - 0.1) << s.integrator;
      EXPECT_GT(slope, -o.settings.alpha / 2 - 0.1) << s.integrator;
    } else {
      EXPECT_NEAR(slope, theory, 0.1) << s.integrator;
      EXPECT_NEAR(slope_rel, 2 * theory, 0.2) << s.integrator;
    }
    EXPECT_EQ(s.reached_target, 1) << s.integrator;  // the worst final RMSE is every run's target
    std::printf("  %s: RMSE slope %.3f, relMSE slope %.3f over passes\n", s.integrator.c_str(),
                slope, slope_rel);
  }
  for (const char* f :
       {"summary.md", "summary.csv", "convergence.png", "images.png", "log_backward_1.csv",
        "log_forward_1.csv", "log_photon_1.csv", "backward.exr", "forward.exr", "photon.exr"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(o.out_dir) / f)) << f;
  std::vector<LogRow> log = read_convergence_log(o.out_dir + "/log_backward_1.csv");
  EXPECT_TRUE(log.back().has_error);
}

TEST(Converge, RepeatsGiveErrorBarsAndACachedReference) {
  // No reference given: one is rendered with backward and cached next to the scene (a copy in
  // the scratch directory), then reused.
  std::filesystem::path dir = scratch_dir();
  std::string scene = (dir / "box.json").string();
  std::filesystem::copy_file(source_path("scenes/furnace_passive.json"), scene);
  std::filesystem::create_directories(dir / "data");
  std::filesystem::copy_file(source_path("scenes/data/CIE_D65_300_780.csv"),
                             dir / "data/CIE_D65_300_780.csv");
  StudyOptions o;
  o.integrators = {"backward", "forward"};
  o.seconds = 0.5;
  o.repeats = 2;
  o.reference_seconds = 2;
  o.out_dir = (dir / "study").string();
  o.show_progress = false;
  o.plot = false;
  StudyResult r = run_convergence_study(scene, o);
  EXPECT_TRUE(std::filesystem::exists(dir / "box.reference.exr"));
  EXPECT_NE(r.reference_description.find("box.reference.exr"), std::string::npos);
  for (const IntegratorSummary& s : r.summaries) {
    EXPECT_EQ(s.runs, 2);
    EXPECT_GT(s.final_rmse_sd, 0) << s.integrator;  // two seeds, two different errors
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "study/log_forward_2.csv"));
  StudyResult again = run_convergence_study(scene, o);
  EXPECT_NE(again.reference_description.find("(cached"), std::string::npos)
      << again.reference_description;
}

TEST(Converge, BadArgumentsGiveOneLine) {
  std::string out = (scratch_dir() / "out").string();
  auto check = [&](const std::string& args, const std::string& expected) {
    auto r = run_kasha("converge " + args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  };
  std::string furnace = source_path("scenes/furnace_passive.json");
  check(furnace + " --integrators backward,sideways --time 1 -o " + out,
        "unknown integrator \"sideways\"");
  check(source_path("scenes/cornell_box.json") + " --time 1 --reference furnace -o " + out,
        "is not an analytic furnace: ");
  check(furnace + " --time 1 --reference /nonexistent/ref.exr -o " + out,
        "--reference /nonexistent/ref.exr: no such file");
  std::string file = write_file("a_file", "x");
  check(furnace + " --time 1 --reference furnace -o " + file + "/sub",
        file + " is not a directory");
}
