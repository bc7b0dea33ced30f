// `mpirun -np K kasha render …` end to end (mpi/): on 2 and 3 ranks (oversubscribed on one machine,
// a device each) every integrator writes the one-process EXR byte for byte; a rank that fails to
// set up, or dies mid-render, ends the job with kasha's one line and a non-zero exit, and Ctrl-C on
// rank 0 writes the image so far. Skipped without an MPI build or an Open MPI mpirun.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "test_support.h"

namespace {

using Clock = std::chrono::steady_clock;

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct Shell {
  int exit_code = 0;
  std::string err;
  double seconds = 0;
};

// A shell command line with stdout and stderr kept; `timeout` guards every mpirun, so a hang
// fails the test (exit 124) instead of stalling the suite.
Shell shell(const std::string& command) {
  const std::string err = (kasha::test::scratch_dir() / "stderr.txt").string();
  const auto t0 = Clock::now();
  const int status =
      std::system((command + " > /dev/null 2> " + quoted(err) + " < /dev/null").c_str());
  Shell r;
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = slurp(err);
  return r;
}

// Open MPI's mpirun, as root too (these tests run in containers), ranks beyond the cores allowed.
const char* const kAsRoot = "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ";
std::string mpirun() {
  return kAsRoot + std::string("timeout -s TERM 120 ") + KASHA_MPIEXEC + " --oversubscribe";
}

// Why these tests cannot run here, or empty.
std::string missing_mpi() {
#ifndef KASHA_HAVE_MPI
  return "kasha is built without MPI (KASHA_MPI=OFF)";
#else
  static const std::string why = [] {
    if (std::string(KASHA_MPIEXEC).empty()) return std::string("no mpirun found at configure time");
    const std::string version = (kasha::test::scratch_dir() / "mpirun_version.txt").string();
    if (std::system(
            (kAsRoot + std::string(KASHA_MPIEXEC) + " --version > " + quoted(version) + " 2>&1")
                .c_str()) != 0 ||
        (slurp(version).find("Open MPI") == std::string::npos &&
         slurp(version).find("OpenRTE") == std::string::npos))
      return std::string(KASHA_MPIEXEC) + " is not Open MPI's mpirun";
    return std::string();
  }();
  return why;
#endif
}

#define SKIP_WITHOUT_MPI()                 \
  do {                                     \
    const std::string why = missing_mpi(); \
    if (!why.empty()) GTEST_SKIP() << why; \
  } while (0)

std::string render_args(const std::string& extra, const std::string& out) {
  return "render " + quoted(kasha::test::source_path("scenes/cornell_box.json")) + " " + extra +
         " -o " + quoted(out);
}

// Few samples a pass, so each run takes seconds; photon mapping needs photons enough for several
// chunks a pass (of at least 2^15 photons each), so that the other ranks trace some of them.
struct Case {
  std::string integrator, options;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.integrator << " " << c.options;
}

class MpiRender : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST_P(MpiRender, TwoAndThreeRanksWriteTheOneProcessFile) {
  SKIP_WITHOUT_MPI();
  const Case& c = GetParam();
  const std::string options = "--integrator " + c.integrator + " " + c.options;
  const std::string one = (kasha::test::scratch_dir() / "one.exr").string();
  Shell r = shell(std::string(KASHA_BINARY) + " " + render_args(options, one));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string expected = slurp(one);
  ASSERT_GT(expected.size(), 1000u);
  for (int ranks : {2, 3}) {
    const std::string out =
        (kasha::test::scratch_dir() / ("ranks" + std::to_string(ranks) + ".exr")).string();
    r = shell(mpirun() + " -np " + std::to_string(ranks) + " " + KASHA_BINARY + " " +
              render_args(options, out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Every rank's device is a lane of rank 0's render.
    EXPECT_NE(r.err.find("rank " + std::to_string(ranks - 1) + " device 0 ("), std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("kasha: error"), std::string::npos) << r.err;
    EXPECT_TRUE(slurp(out) == expected) << ranks << " ranks wrote another file than one process";
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, MpiRender,
                         ::testing::Values(Case{"backward", "--spp 1 --passes 3"},
                                           Case{"forward", "--photons 50000 --passes 3"},
                                           Case{"photon", "--photons 1000000 --spp 1 --passes 2"},
                                           Case{"vcm", "--passes 3"}),
                         [](const auto& info) { return info.param.integrator; });

// KASHA_TEST_KILL_RANK=1: rank 1 dies by SIGKILL as its second pass is asked of it. mpirun then
// sends SIGTERM to the others; rank 0, interrupted, finds rank 1 not answering and names it.
// Open MPI sends SIGKILL 1 s after its SIGTERM; rank 0 first finishes the pass in flight, which on
// a cold kernel cache and a busy machine (CI) can include compiling a kernel variant for seconds,
// so the test gives it 5 s (Open MPI waits that long on the killed rank, too): what it checks is
// kasha's line, not how long Open MPI waits.
TEST(Mpi, ARankKilledMidRenderEndsTheJobWithOneLine) {
  SKIP_WITHOUT_MPI();
  const std::string out = (kasha::test::scratch_dir() / "killed.exr").string();
  Shell r = shell("KASHA_TEST_KILL_RANK=1 " + mpirun() + " --mca odls_base_sigkill_timeout 5" +
                  " -np 2 " + KASHA_BINARY + " " +
                  render_args("--integrator backward --spp 1 --passes 100", out));
  EXPECT_NE(r.exit_code, 0) << r.err;
  EXPECT_NE(r.exit_code, 124) << "the job hung: " << r.err;
  EXPECT_LT(r.seconds, 60);
  EXPECT_NE(r.err.find("kasha: error: rank 1: no answer within 0.5 s of the interrupt"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::ifstream(out).good()) << "no image from a failed job";
}

// A rank that cannot set up (here: its own, missing scene, given by mpirun's MPMD form) is named
// in rank 0's one line, and nothing is written.
TEST(Mpi, ARankThatFailsToSetUpIsNamed) {
  SKIP_WITHOUT_MPI();
  const std::string out = (kasha::test::scratch_dir() / "failed.exr").string();
  const std::string args = "render --integrator backward --spp 1 --passes 2 -o " + quoted(out);
  Shell r = shell(mpirun() + " -np 1 " + KASHA_BINARY + " " + args + " " +
                  quoted(kasha::test::source_path("scenes/cornell_box.json")) + " : -np 1 " +
                  KASHA_BINARY + " " + args + " /nonexistent.json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("kasha: error: rank 1: /nonexistent.json: cannot open file"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("kasha: error", r.err.find("kasha: error") + 1), std::string::npos)
      << "one line: " << r.err;
  EXPECT_FALSE(std::ifstream(out).good());
}

// Ctrl-C on rank 0 (SIGINT to it alone: `timeout` wraps rank 0 in mpirun's MPMD form): the other
// ranks are told, end their passes early, and rank 0 writes the image so far and exits 130,
// which mpirun returns.
TEST(Mpi, InterruptOnRankZeroWritesTheImageSoFar) {
  SKIP_WITHOUT_MPI();
  const std::string out = (kasha::test::scratch_dir() / "interrupted.exr").string();
  const std::string args = render_args("--integrator backward --spp 1 --passes 100000", out);
  Shell r = shell(mpirun() + " -np 1 timeout --preserve-status -s INT 6 " + KASHA_BINARY + " " +
                  args + " : -np 2 " + KASHA_BINARY + " " + args);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted: writing the image after"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("kasha: error"), std::string::npos) << r.err;
  EXPECT_GT(slurp(out).size(), 1000u);
}
