#pragma once
// Runs one of the Python scripts compiled into kasha (plots) with Debian's /usr/bin/python3 and
// matplotlib: the script is written into `dir`, its output goes to dir/plot.log.
#include <string>
#include <vector>

namespace kasha {

// Throws kasha::Error starting with `who` when the script fails.
void run_embedded_python(const std::string& script, const std::string& dir,
                         const std::vector<std::string>& args, const std::string& who);

}  // namespace kasha
