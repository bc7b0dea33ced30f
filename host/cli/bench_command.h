#pragma once
// `kasha bench`: the fixed bench scenes × the physical integrators, each for a fixed time on each
// listed device in turn (LuxMark-like): throughput, rays, time, memory and a validated image per
// run, a score per device, a table on the terminal and optionally a JSON record.
#include <string>

namespace kasha {

struct BenchArgs {
  std::string device = "0";    // --device: an index, indices (0,1) or all
  double seconds = 10;         // --time: per run
  std::string json;            // --json: the record
  std::string scenes;          // --scenes: the scenes folder (default: the source tree's)
  double make_references = 0;  // > 0: render the references for this long each instead
  std::string version;         // kasha's, for the record
};

// Exit 0 when every run's image is valid; a run that is not valid is a run error (exit 1, after
// the table and the record are written); Ctrl-C: 130, after the runs so far are written.
int run_bench_command(const BenchArgs& args);

}  // namespace kasha
