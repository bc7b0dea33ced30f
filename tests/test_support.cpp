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

std::string source_path(const std::string& relative) {
  return std::string(KASHA_SOURCE_DIR) + "/" + relative;
}

static std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_kasha(const std::string& args) {
  return run_kasha_env("", args);
}

CommandResult run_kasha_env(const std::string& env, const std::string& args,
                            int interrupt_after_s) {
  std::string out = (scratch_dir() / "stdout.txt").string(),
              err = (scratch_dir() / "stderr.txt").string();
  std::string prefix = env.empty() ? "" : "env " + env + " ";
  if (interrupt_after_s > 0)
    prefix += "timeout --preserve-status -s INT " + std::to_string(interrupt_after_s) + " ";
  std::string cmd =
      prefix + KASHA_BINARY + " " + args + " > '" + out + "' 2> '" + err + "' < /dev/null";
  int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
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
