#pragma once
// Helpers shared by the tests: scratch files, running the kasha binary, expecting kasha::Error.
#include <gtest/gtest.h>

#include <complex>
#include <filesystem>
#include <string>

#include "core/error.h"

namespace kasha::test {

// A fresh scratch directory for the calling test.
std::filesystem::path scratch_dir();
// Writes `text` to scratch_dir()/name and returns the path.
std::string write_file(const std::string& name, const std::string& text);
std::string source_path(const std::string& relative);  // inside the source tree
std::string shell_quoted(const std::string& s);        // for run_kasha's argument string

// Unpolarized Fresnel reflectance of a smooth interface of complex relative index m (far side
// over near side), cos_i > 0, from Born & Wolf's form (r_s, r_p through sqrt(m² − sin²θ)): the
// tests' ground truth, written apart from the kernels' fresnel.h.
double fresnel_reference(double cos_i, std::complex<double> m);

struct CommandResult {
  int exit_code = 0;
  std::string out, err;
};
// Runs the kasha binary with `args` (a shell-quoted string).
CommandResult run_kasha(const std::string& args);
// Same, with environment assignments ("NAME=value ...") and, when interrupt_after_s > 0, a SIGINT
// sent after that many seconds, as Ctrl-C would.
CommandResult run_kasha_env(const std::string& env, const std::string& args,
                            int interrupt_after_s = 0);
// Runs kasha in a process group of its own and sends `signal` ("INT", "TERM") to the group once
// after `after_s` seconds, as a terminal does for Ctrl-C; `env` as above (may be empty).
CommandResult run_kasha_signalled(const std::string& env, const std::string& args,
                                  const std::string& signal, double after_s);

// Runs f and returns the kasha::Error message it throws (fails the test if it throws nothing).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a kasha::Error";
  return "";
}

}  // namespace kasha::test
