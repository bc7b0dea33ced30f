#pragma once
// The host's peak resident memory, per stretch of work: `kasha bench` reports each run's own peak.
#include <cstddef>

namespace kasha {

// Starts a new peak from the current resident size (Linux: /proc/self/clear_refs, "5" resets
// the high-water mark getrusage reports). Returns false where that is not possible: the peak is
// then the process's since it started.
bool reset_peak_resident_memory();

// Bytes: getrusage's ru_maxrss, the peak resident set size since the last reset.
size_t peak_resident_memory_bytes();

}  // namespace kasha
