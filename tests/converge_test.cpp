// `kasha converge`: rates of convergence on a furnace match theory, the study writes what it
// promises, and bad arguments give one clear line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render/convergence_log.h"
#include "render/convergence_study.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Converge, FurnaceSlopesMatchTheory) {
  StudyOptions o;
  o.seconds = 3;
  o.reference = "furnace";
  o.settings.spp = 4;
  o.settings.photons = 1 << 14;
  o.out_dir = (scratch_dir() / "study").string();
  o.show_progress = false;
  StudyResult r = run_convergence_study(source_path("scenes/furnace_fluorescent.json"), o);
  ASSERT_EQ(r.summaries.size(), 3u);
  for (const IntegratorSummary& s : r.summaries) {
    double theory = s.integrator == "photon" ? -1.0 / 3.0 : -0.5;
    EXPECT_NEAR(s.slope_rmse, theory, 0.1) << s.integrator;
    EXPECT_NEAR(s.slope_relmse, 2 * theory, 0.2) << s.integrator;
    EXPECT_EQ(s.reached_target, 1) << s.integrator;  // the worst final RMSE is every run's target
    std::printf("  %s: RMSE slope %.3f, relMSE slope %.3f\n", s.integrator.c_str(), s.slope_rmse,
                s.slope_relmse);
  }
  for (const char* f :
       {"summary.md", "summary.csv", "convergence.png", "images.png", "log_backward_1.csv",
        "log_forward_1.csv", "log_photon_1.csv", "backward.exr", "forward.exr", "photon.exr"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(o.out_dir) / f)) << f;
  std::vector<LogRow> log = read_convergence_log(o.out_dir + "/log_backward_1.csv");
  EXPECT_GT(log.size(), 10u);
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
  check(furnace + " --time 1 --reference furnace -o " + file + "/sub", "cannot create directory");
}
