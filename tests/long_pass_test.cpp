// A legal, very long pass — 2^31 - 1 light subpaths, hours on the test CPU — stops on Ctrl-C
// within a second or two and writes the image so far, and its memory stays within --memory
// (plus the scene, the film and the runtime) however large --photons is: vcm's light pass runs in
// chunks that the store's budget bounds, polled for interrupts between launches.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "image/exr_io.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace kasha;

namespace {

struct Interrupted {
  int exit_code = -1;
  double peak_bytes = 0;    // VmHWM just before the signal
  double exit_seconds = 0;  // from the signal to kasha's exit
  std::string err;
};

// kasha in a process group of its own (as test::run_kasha_signalled), its peak resident memory
// read from /proc just before SIGINT goes to the group `after_s` seconds in.
Interrupted render_and_interrupt(const std::string& args, double after_s) {
  const fs::path dir = test::scratch_dir();
  const std::string err = (dir / "long_pass_err.txt").string(),
                    figures = (dir / "long_pass_figures.txt").string();
  std::ostringstream script;
  script << "setsid " << KASHA_BINARY << " " << args << " > /dev/null 2> '" << err
         << "' < /dev/null &\n"
         << "p=$!\nsleep " << after_s << "\n"
         << "hwm=$(awk '/VmHWM/ {print $2}' /proc/$p/status)\n"
         << "t0=$(date +%s.%N)\nkill -s INT -- -$p\nwait $p\nrc=$?\nt1=$(date +%s.%N)\n"
         << "echo \"$rc $hwm $t0 $t1\" > '" << figures << "'\n";
  std::string quoted;
  for (char c : script.str()) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  std::system(("bash -c '" + quoted + "'").c_str());
  Interrupted r;
  std::ifstream in(figures);
  double kib = 0, t0 = 0, t1 = 0;
  in >> r.exit_code >> kib >> t0 >> t1;
  r.peak_bytes = kib * 1024;
  r.exit_seconds = t1 - t0;
  std::ifstream e(err);
  std::stringstream text;
  text << e.rdbuf();
  r.err = text.str();
  return r;
}

}  // namespace

TEST(LongPass, VcmStopsOnCtrlCWithinItsMemoryBudget) {
  const std::string scene = test::source_path("scenes/cornell_box.json");
  const fs::path out = test::scratch_dir() / "long_pass.exr";
  const std::string common = "render '" + scene + "' --memory 64MiB -o '" + out.string() + "'";
  // The kernels built first, so that the signal lands in the pass, not in PoCL's compiler.
  ASSERT_EQ(test::run_kasha(common + " --passes 1 --photons 4096").exit_code, 0);
  // The runtime, scene and film alone: one light subpath an iteration, passes until the signal.
  const Interrupted base = render_and_interrupt(common + " --passes 100000 --photons 1", 4);
  ASSERT_EQ(base.exit_code, 130) << base.err;
  fs::remove(out);
  const Interrupted big = render_and_interrupt(common + " --passes 1 --photons 2147483647", 6);
  std::printf(
      "base %.0f MiB, 2^31 photons %.0f MiB (--memory 64MiB), stopped %.2f s after Ctrl-C\n",
      base.peak_bytes / 1048576, big.peak_bytes / 1048576, big.exit_seconds);
  EXPECT_EQ(big.exit_code, 130) << big.err;
  EXPECT_NE(big.err.find("interrupted: writing the image after 1 passes"), std::string::npos)
      << big.err;
  EXPECT_EQ(read_exr(out.string()).width, 256);
  // The pass would take hours; a bound far from the measured ~0.6 s that a pass ignoring Ctrl-C
  // (minutes, before the light pass was polled) cannot meet.
  EXPECT_LT(big.exit_seconds, 10.0);
  // The store, its grid and the chunk's table within the budget, plus launch-sized scratch.
  EXPECT_LT(big.peak_bytes, base.peak_bytes + 64.0 * 1048576 + 32.0 * 1048576);
}
