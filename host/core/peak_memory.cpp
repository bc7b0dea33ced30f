#include "core/peak_memory.h"

#include <sys/resource.h>

#include <fstream>

namespace kasha {

bool reset_peak_resident_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  clear.close();
  return static_cast<bool>(clear);
}

size_t peak_resident_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<size_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace kasha
