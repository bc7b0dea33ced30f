#pragma once
// A warning: one line `kasha: warning: what` on stderr; the command goes on.
#include <cstdio>
#include <string>

namespace kasha {

inline void warn(const std::string& what) {
  std::fprintf(stderr, "kasha: warning: %s\n", what.c_str());
}

}  // namespace kasha
