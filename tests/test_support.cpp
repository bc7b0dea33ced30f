#include "test_support.h"

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>

namespace kasha::test {

std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path(KASHA_TEST_TMP) /
                              (std::string(info->test_suite_name()) + "." + info->name());
  static std::string last;
  if (last != dir.string()) {
    std::filesystem::remove_all(dir);
    last = dir.string();
  }
  std::filesystem::create_directories(dir);
  return dir;
}

std::string write_file(const std::string& name, const std::string& text) {
  std::filesystem::path p = scratch_dir() / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p.string();
}

std::string shell_quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string source_path(const std::string& relative) {
  return std::string(KASHA_SOURCE_DIR) + "/" + relative;
}

static std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {
CommandResult finish(int status, const std::string& out, const std::string& err) {
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}
}  // namespace

CommandResult run_kasha(const std::string& args) {
  return run_kasha_env("", args);
}

CommandResult run_kasha_env(const std::string& env, const std::string& args,
                            int interrupt_after_s) {
  if (interrupt_after_s > 0) return run_kasha_signalled(env, args, "INT", interrupt_after_s);
  std::string out = (scratch_dir() / "stdout.txt").string(),
              err = (scratch_dir() / "stderr.txt").string();
  std::string prefix = env.empty() ? "" : "env " + env + " ";
  std::string cmd =
      prefix + KASHA_BINARY + " " + args + " > '" + out + "' 2> '" + err + "' < /dev/null";
  return finish(std::system(cmd.c_str()), out, err);
}

// kasha in a process group of its own (setsid), the signal sent to that group once, as a
// terminal sends Ctrl-C: kasha and its children (a kernel build's linker, a plot) get it once
// each. timeout(1) signals the child and then its group, so kasha got it twice within
// microseconds, which can meet the default action in the instant PoCL's LLVM handler has reset
// it (host/core/interrupt.cpp): a harness artefact, not what a user's Ctrl-C does.
CommandResult run_kasha_signalled(const std::string& env, const std::string& args,
                                  const std::string& signal, double after_s) {
  const std::string out = (scratch_dir() / "stdout.txt").string(),
                    err = (scratch_dir() / "stderr.txt").string();
  // The timer's shell holds no standard stream (an orphaned sleep would keep a pipe open) and is
  // stopped, with its sleep, as soon as kasha ends.
  std::ostringstream script;
  script << "setsid env " << env << " " << KASHA_BINARY << " " << args << " > '" << out << "' 2> '"
         << err << "' < /dev/null &\n"
         << "p=$!\n"
         << "(exec > /dev/null 2>&1 < /dev/null; sleep " << after_s << " && kill -s " << signal
         << " -- -$p) &\n"
         << "k=$!\n"
         << "wait $p\nrc=$?\npkill -P $k 2> /dev/null\nkill $k 2> /dev/null\nexit $rc\n";
  std::string quoted;  // the script as one single-quoted shell word
  for (char c : script.str()) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return finish(std::system(("bash -c '" + quoted + "'").c_str()), out, err);
}

}  // namespace kasha::test

namespace kasha::test {

double fresnel_reference(double cos_i, std::complex<double> m) {
  const double sin2 = 1 - cos_i * cos_i;
  const std::complex<double> root = std::sqrt(m * m - sin2);
  const std::complex<double> rs = (cos_i - root) / (cos_i + root);
  const std::complex<double> rp = (m * m * cos_i - root) / (m * m * cos_i + root);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

}  // namespace kasha::test
