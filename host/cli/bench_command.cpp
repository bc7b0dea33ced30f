// `kasha bench`: the fixed bench scenes × the physical integrators, each for a fixed time on each
// listed device in turn (LuxMark-like): throughput, rays, time, memory and a validated image per
// run, a score per device, a table on the terminal and optionally a JSON record.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "bench/bench_reference.h"
#include "bench/bench_report.h"
#include "bench/bench_run.h"
#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "cli/render_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_set.h"
#include "core/peak_memory.h"
#include "opencl/device_list.h"
#include "render/device_set.h"
#include "study/reference_image.h"

namespace kasha {

struct BenchArgs {
  std::string device = "0";    // --device: an index, indices (0,1) or all
  double seconds = 10;         // --time: per run
  std::string json;            // --json: the record
  std::string scenes;          // --scenes: the scenes folder (default: the source tree's)
  double make_references = 0;  // > 0: render the references for this long each instead
  std::string version;         // kasha's, for the record
};

namespace {

// The device sets benchmarked: each listed device on its own (once, however often it is
// named), then, with several listed, all of them together rendering each image.
std::vector<std::vector<int>> bench_device_sets(const std::vector<int>& listed) {
  std::vector<std::vector<int>> sets;
  for (size_t i = 0; i < listed.size(); ++i)
    if (std::find(listed.begin(), listed.begin() + i, listed[i]) == listed.begin() + i)
      sets.push_back({listed[i]});
  if (listed.size() > 1) sets.push_back(listed);
  return sets;
}

// --make-references: every EXR reference rendered on the first listed device, all written
// together once complete.
int make_references(int device, double seconds, const std::vector<LoadedBenchScene>& scenes,
                    OutputSet& outputs) {
  for (const LoadedBenchScene& s : scenes)
    if (!s.reference_path.empty()) outputs.file("--make-references", s.reference_path);
  DeviceSet set(std::vector<int>{device});
  ClContext& cl = set.main();
  for (const LoadedBenchScene& s : scenes) {
    if (s.reference_path.empty()) continue;
    std::fprintf(stderr, "bench: the reference of %s, %dx%d, %g s on %s\n", s.path.c_str(),
                 s.bench->width, s.bench->height, seconds, cl.info().name.c_str());
    ReferenceInfo info;
    Image image = render_reference(set, s.scene, seconds, 0x7e1f, info, true);
    if (interrupt_requested()) throw Interrupted();  // a short reference is not one
    outputs.write(s.reference_path,
                  [&](const std::string& tmp) { write_reference(tmp, image, info); });
  }
  outputs.commit();
  for (const LoadedBenchScene& s : scenes)
    if (!s.reference_path.empty()) std::fprintf(stderr, "wrote %s\n", s.reference_path.c_str());
  return 0;
}

}  // namespace

static int run_bench_command(const BenchArgs& a) {
  install_interrupt_handler();
  OutputSet outputs;
  outputs.file("--json", a.json);
  const std::vector<int> devices = parse_device_list(a.device);
  const std::string dir = a.scenes.empty() ? default_bench_scenes_dir() : a.scenes;
  // Every scene and reference is read, and checked, before any rendering; the scenes are let go
  // again (and loaded anew for their runs), so each run's host memory is its own scene's.
  std::vector<LoadedBenchScene> scenes;
  for (const BenchScene& b : bench_scenes()) {
    outputs.input((std::string(dir) + "/" + b.file), "a bench scene");
    scenes.push_back(load_bench_scene(b, dir));
    if (a.make_references > 0) continue;
    load_bench_reference(scenes.back());
    if (!scenes.back().reference_path.empty())
      outputs.input(scenes.back().reference_path, "a bench reference");
    scenes.back().scene = Scene();
  }
  outputs.inputs_read("a bench scene's material or data file");
  if (a.make_references > 0)
    return make_references(devices.front(), a.make_references, scenes, outputs);

  BenchRecord record;
  record.version = a.version;
  record.seconds = a.seconds;
  record.scenes_dir = dir;
  record.host_memory_per_run = reset_peak_resident_memory();
  for (const LoadedBenchScene& s : scenes)
    record.scenes.push_back({s.bench->name, s.bench->file, s.reference_description, s.bench->width,
                             s.bench->height, s.triangles, s.bench->bound,
                             bench_integrators(*s.bench)});
  size_t total = 0, done = 0;
  for (const LoadedBenchScene& s : scenes) total += bench_integrators(*s.bench).size();
  const std::vector<std::vector<int>> sets = bench_device_sets(devices);
  total *= sets.size();
  if (sets.size() > 1) record.together = sets.back();
  for (const std::vector<int>& indices : sets) {
    if (!record.complete) break;
    DeviceSet device_set(indices);
    if (indices.size() == 1) record.devices.push_back(device_set.main().info());
    std::string label;
    for (int i : indices) label += (label.empty() ? "" : "+") + std::to_string(i);
    for (LoadedBenchScene& s : scenes) {
      if (!record.complete) break;
      s.scene = load_bench_scene(*s.bench, dir).scene;
      std::vector<BenchDevice> set;
      for (const RenderLane& lane : device_set.upload(s.scene))
        set.push_back({lane.cl, lane.scene});
      for (const std::string& integrator : bench_integrators(*s.bench)) {
        std::fprintf(stderr, "bench [%zu/%zu]: %s, %s, device %s (%s), %dx%d, %g s\n", ++done,
                     total, s.bench->name.c_str(), integrator.c_str(), label.c_str(),
                     device_set.names().c_str(), s.bench->width, s.bench->height, a.seconds);
        record.runs.push_back(bench_on_devices(s, integrator, set, a.seconds, true));
        if (record.runs.back().interrupted || interrupt_requested()) {
          record.complete = false;
          break;
        }
      }
      device_set.release_scene();  // its buffers go with the scene
      s.scene = Scene();
    }
  }

  std::fputs(bench_table(record).c_str(), stdout);
  std::fflush(stdout);
  if (!a.json.empty())
    outputs.write(a.json, [&](const std::string& tmp) {
      write_text_atomically(tmp, bench_json(record).dump(1) + "\n");
    });
  outputs.commit();
  if (!a.json.empty()) std::fprintf(stderr, "wrote %s\n", a.json.c_str());
  if (!record.complete) return kInterruptExitCode;
  size_t invalid = 0;
  const BenchRun* first = nullptr;
  for (const BenchRun& r : record.runs)
    if (!r.valid()) ++invalid, first = first ? first : &r;
  if (first)
    throw Error("bench: " + std::to_string(invalid) + " of " + std::to_string(record.runs.size()) +
                " runs are not valid, the first " + first->scene + " by " + first->integrator +
                " on device " + std::to_string(first->devices.front()) + ": " +
                first->validation.why);
  return 0;
}

static Command::Action declare_bench(CLI::App& app) {
  auto a = std::make_shared<BenchArgs>();
  a->version = KASHA_VERSION;
  app.add_option("--device", a->device,
                 "OpenCL device index, indices (0,1) or all, each benchmarked in turn (default 0)")
      ->check(cli::device_list());
  app.add_option("--time", a->seconds, "rendering seconds per run (default 10)")
      ->check(cli::positive_number(cli::kMaxSeconds));
  CLI::Option* json = app.add_option("--json", a->json, "the record as JSON");
  app.add_option("--scenes", a->scenes,
                 "the folder holding the bench scenes and scenes/bench/ references (default: the "
                 "source tree's scenes/)");
  app.add_option("--make-references", a->make_references,
                 "instead of benchmarking, render the bench scenes' reference images for this "
                 "many seconds each (the reference integrator, first listed device)")
      ->check(cli::positive_number(cli::kMaxSeconds))
      ->excludes(json);
  return [a] { return run_bench_command(*a); };
}

KASHA_REGISTER_COMMAND(
    bench, "bench",
    "fixed scenes × the physical integrators for a fixed time on each device: throughput, rays, "
    "time, memory, a validated image per run and a score per device",
    12, false, declare_bench);

}  // namespace kasha
