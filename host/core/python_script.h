#pragma once
// Runs one of the Python scripts compiled into kasha (plots) with Debian's /usr/bin/python3 and
// matplotlib, as a child process (no shell, no files of its own: the script is given with -c, its
// output is read through a pipe). SIGINT and SIGTERM during the run stop the child and are waited
// out: the call then throws kasha::Interrupted, so nothing of the run stays behind.
#include <string>
#include <vector>

namespace kasha {

// `args` are the script's sys.argv[1:]; `input` is its stdin (read it as /dev/stdin). Throws
// kasha::Error starting with `who` when the script cannot run or fails, with its last error line.
void run_embedded_python(const std::string& script, const std::vector<std::string>& args,
                         const std::string& who, const std::string& input = "");

}  // namespace kasha
