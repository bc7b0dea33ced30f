#pragma once
// What `kasha bench` reports: the score per device, the terminal table and the JSON record
// (README, "kasha bench": every field and its unit).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_run.h"
#include "opencl/device.h"

namespace kasha {

// A bench scene as the record describes it.
struct BenchSceneRecord {
  std::string name, file, reference;  // the reference's description
  int width = 0, height = 0;
  size_t triangles = 0;
  double bound = 0;
  std::vector<std::string> integrators;
};

struct BenchRecord {
  std::string version;  // kasha's
  double seconds = 0;   // asked per run (--time)
  std::string scenes_dir;
  std::vector<BenchSceneRecord> scenes;
  std::vector<DeviceInfo> devices;  // in the order benchmarked, each on its own
  // With several devices listed (--device 0,1 or 0,0): the list, whose runs render each image on
  // all of them together (render/render_job.h) after each device's own runs.
  std::vector<int> together;
  std::vector<BenchRun> runs;
  bool complete = true;             // false when Ctrl-C stopped it
  bool host_memory_per_run = true;  // each run's own peak (else the process's so far)
};

// The geometric mean over `runs` of samples (camera paths + photons) per second, or 0 when a run
// is not valid (or there is none): the ratio of two devices' scores is then the geometric mean
// of their per-run speed ratios, whatever the runs' units.
double bench_score(const std::vector<BenchRun>& runs);

// The runs made on device set {index}, and on a set of devices.
std::vector<BenchRun> runs_on(const BenchRecord& record, int index);
std::vector<BenchRun> runs_on_set(const BenchRecord& record, const std::vector<int>& devices);

std::string bench_table(const BenchRecord& record);
nlohmann::json bench_json(const BenchRecord& record);

}  // namespace kasha
