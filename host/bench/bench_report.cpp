#include "bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "bench/bench_validation.h"
#include "core/printable.h"

namespace kasha {

double bench_score(const std::vector<BenchRun>& runs) {
  if (runs.empty()) return 0;
  double log_sum = 0;
  for (const BenchRun& r : runs) {
    const double rate = r.per_second(r.samples());
    if (!r.valid() || !(rate > 0)) return 0;
    log_sum += std::log(rate);
  }
  return std::exp(log_sum / runs.size());
}

std::vector<BenchRun> runs_on_set(const BenchRecord& record, const std::vector<int>& devices) {
  std::vector<BenchRun> out;
  for (const BenchRun& r : record.runs)
    if (r.devices == devices) out.push_back(r);
  return out;
}

std::vector<BenchRun> runs_on(const BenchRecord& record, int index) {
  return runs_on_set(record, {index});
}

namespace {

// "0+1", "0+0".
std::string device_set_name(const std::vector<int>& devices) {
  std::string out;
  for (int d : devices) out += (out.empty() ? "" : "+") + std::to_string(d);
  return out;
}

// The definitions every run on the device was built with, in the first run's order: the part of
// the build options that does not depend on the scene.
std::string common_build_options(const std::vector<BenchRun>& runs) {
  if (runs.empty()) return "";
  auto tokens = [](const std::string& options) {
    std::vector<std::string> out;
    std::istringstream in(options);
    for (std::string word; in >> word;)
      if (word == "-D" && in >> word) out.push_back(word);
    return out;
  };
  std::string out;
  for (const std::string& d : tokens(runs[0].build_options)) {
    bool everywhere = true;
    for (const BenchRun& r : runs) {
      std::vector<std::string> t = tokens(r.build_options);
      everywhere = everywhere && std::find(t.begin(), t.end(), d) != t.end();
    }
    if (everywhere) out += (out.empty() ? "-D " : " -D ") + d;
  }
  return out;
}

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

std::string bench_table(const BenchRecord& record) {
  std::ostringstream out;
  char line[512];
  auto table = [&](const std::vector<BenchRun>& runs) {
    std::snprintf(
        line, sizeof line, "%-19s %-8s %6s %7s %9s %9s %9s %9s %9s %7s %7s %7s %7s %9s %9s %s\n",
        "scene", "integr.", "passes", "build s", "paths/s", "photons/s", "closest/s", "shadow/s",
        "gather/s", "dev s", "host s", "dev MB", "host MB", "relMSE", "block rel", "valid");
    out << line;
    for (const BenchRun& r : runs) {
      std::snprintf(
          line, sizeof line,
          "%-19s %-8s %6d %7.2f %9.3g %9.3g %9.3g %9.3g %9.3g %7.2f %7.2f %7.0f %7.0f %9.3g "
          "%9.3g %s\n",
          r.scene.c_str(), r.integrator.c_str(), r.passes, r.kernel_build_seconds,
          r.per_second(r.camera_paths), r.per_second(r.photons), r.per_second(r.closest_rays),
          r.per_second(r.shadow_rays), r.per_second(r.gather_queries), r.device_seconds,
          r.host_seconds, r.device_memory_bytes / 1e6, r.host_memory_bytes / 1e6,
          r.validation.rel_mse, r.validation.block_rel_mse,
          r.interrupted        ? "interrupted"
          : r.validation.valid ? "yes"
                               : "NO");
      out << line;
    }
    for (const BenchRun& r : runs)
      if (!r.validation.valid)
        out << "  " << r.scene << ", " << r.integrator << ": not valid: " << r.validation.why
            << "\n";
  };
  auto score_line = [&](const std::vector<BenchRun>& runs) {
    const double score = bench_score(runs);
    return score > 0 ? format("%.4g", score) + " samples/s (geometric mean over " +
                           std::to_string(runs.size()) + " runs)"
                     : std::string("0 (a run is not valid)");
  };
  double fastest = 0;
  for (const DeviceInfo& d : record.devices) {
    const std::vector<BenchRun> runs = runs_on(record, d.index);
    out << "device " << d.index << ": " << d.name << " (" << d.platform << ", driver " << d.driver
        << ", " << d.compute_units << " compute units), " << record.seconds << " s a run\n";
    table(runs);
    out << "score of device " << d.index << ": " << score_line(runs) << "\n";
    fastest = std::max(fastest, bench_score(runs));
  }
  if (!record.together.empty()) {
    const std::vector<BenchRun> runs = runs_on_set(record, record.together);
    out << "devices " << device_set_name(record.together) << " together, one image on all\n";
    table(runs);
    out << "score of devices " << device_set_name(record.together)
        << " together: " << score_line(runs);
    if (fastest > 0 && bench_score(runs) > 0)
      out << format(", %.2f× the fastest device alone", bench_score(runs) / fastest);
    out << "\n";
  }
  if (!record.complete) out << "interrupted: the record is incomplete\n";
  return out.str();
}

nlohmann::json bench_json(const BenchRecord& record) {
  using nlohmann::json;
  json j;
  j["kasha_bench"] = 1;
  j["kasha_version"] = record.version;
  j["seconds_per_run"] = record.seconds;
  j["complete"] = record.complete;
  j["validation_block_pixels"] = kValidationBlock;
  j["host_memory_per_run"] = record.host_memory_per_run;
  j["scenes_dir"] = json_text(record.scenes_dir);  // a command-line folder: any bytes
  j["scenes"] = json::array();
  for (const BenchSceneRecord& s : record.scenes)
    j["scenes"].push_back({{"name", s.name},
                           {"file", s.file},
                           {"width", s.width},
                           {"height", s.height},
                           {"triangles", s.triangles},
                           {"reference", s.reference},
                           {"validation_bound", s.bound},
                           {"integrators", s.integrators}});
  j["devices"] = json::array();
  for (const DeviceInfo& d : record.devices) {
    const std::vector<BenchRun> runs = runs_on(record, d.index);
    bool valid = !runs.empty();
    for (const BenchRun& r : runs) valid = valid && r.valid();
    j["devices"].push_back({{"index", d.index},
                            // driver strings: no promise they are UTF-8
                            {"name", json_text(d.name)},
                            {"platform", json_text(d.platform)},
                            {"driver", json_text(d.driver)},
                            {"version", json_text(d.version)},
                            {"type", d.type},
                            {"compute_units", d.compute_units},
                            {"global_memory_bytes", d.global_mem_bytes},
                            {"build_options", common_build_options(runs)},
                            {"runs", runs.size()},
                            {"valid", valid},
                            {"score", bench_score(runs)}});
  }
  j["runs"] = json::array();
  for (const BenchRun& r : record.runs)
    j["runs"].push_back({{"scene", r.scene},
                         {"integrator", r.integrator},
                         {"device", r.devices.front()},
                         {"devices", r.devices},
                         {"width", r.width},
                         {"height", r.height},
                         {"seconds", r.seconds},
                         {"passes", r.passes},
                         {"samples_per_pixel", r.samples_per_pixel},
                         {"kernel_build_seconds", r.kernel_build_seconds},
                         {"startup_seconds", r.startup_seconds},
                         {"camera_paths", r.camera_paths},
                         {"photons", r.photons},
                         {"camera_paths_per_s", r.per_second(r.camera_paths)},
                         {"photons_per_s", r.per_second(r.photons)},
                         {"samples_per_s", r.per_second(r.samples())},
                         {"closest_rays", r.closest_rays},
                         {"shadow_rays", r.shadow_rays},
                         {"rays_per_s", r.per_second(r.closest_rays + r.shadow_rays)},
                         {"closest_rays_per_s", r.per_second(r.closest_rays)},
                         {"shadow_rays_per_s", r.per_second(r.shadow_rays)},
                         {"gather_queries_per_s", r.per_second(r.gather_queries)},
                         {"host_seconds", r.host_seconds},
                         {"device_seconds", r.device_seconds},
                         {"device_memory_bytes", r.device_memory_bytes},
                         {"host_memory_bytes", r.host_memory_bytes},
                         {"build_options", r.build_options},
                         {"rel_mse", r.validation.rel_mse},
                         {"validation_rel_mse", r.validation.block_rel_mse},
                         {"validation_bound", r.validation.bound},
                         {"interrupted", r.interrupted},
                         {"valid", r.valid()}});
  if (!record.together.empty()) {
    const std::vector<BenchRun> runs = runs_on_set(record, record.together);
    bool valid = !runs.empty();
    for (const BenchRun& r : runs) valid = valid && r.valid();
    j["together"] = {{"devices", record.together},
                     {"runs", runs.size()},
                     {"valid", valid},
                     {"score", bench_score(runs)}};
  }
  // The whole record's: the runs of every device set (with one device, its score).
  j["score"] = bench_score(record.runs);
  return j;
}

}  // namespace kasha
