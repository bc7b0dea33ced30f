#include "core/python_script.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/embedded_file.h"
#include "core/error.h"

namespace kasha {

// Single quotes keep every character but the quote itself literal in sh.
static std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void run_embedded_python(const std::string& script, const std::string& dir,
                         const std::vector<std::string>& args, const std::string& who) {
  namespace fs = std::filesystem;
  const fs::path path = fs::path(dir) / script, log = fs::path(dir) / "plot.log";
  std::ofstream(path) << embedded_data(script);
  std::string cmd = "/usr/bin/python3 " + shell_quoted(path.string());
  for (const std::string& a : args) cmd += " " + shell_quoted(a);
  cmd += " > " + shell_quoted(log.string()) + " 2>&1";
  int status = std::system(cmd.c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(who + ": plotting failed (needs /usr/bin/python3 with python3-matplotlib; see " +
                log.string() + ")");
}

}  // namespace kasha
