#pragma once
// The one line that says what the exception in flight was: what the command line prints after
// `kasha: error: ` and what an MPI rank sends rank 0 when its work fails. Call it inside a catch
// block; an interrupt reads "interrupted", an OpenCL error names its code.
#include <string>

namespace kasha {

std::string failure_text();

}  // namespace kasha
