#include "study/convergence_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/printable.h"
#include "core/python_script.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "render/render_job.h"
#include "study/convergence_log.h"
#include "study/furnace.h"
#include "study/reference_image.h"

namespace kasha {

namespace fs = std::filesystem;

namespace {

void check_directory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw Error("-o " + dir + ": cannot create directory" + (ec ? ": " + error_words(ec) : ""));
  fs::path probe = fs::path(dir) / ".kasha-write-test";
  std::ofstream test(probe);
  if (!test) throw Error("-o " + dir + ": directory is not writable");
  test.close();
  fs::remove(probe, ec);
}

struct Stats {
  double mean = 0, sd = 0;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  std::vector<double> ok;
  for (double x : v)
    if (std::isfinite(x)) ok.push_back(x);
  if (ok.empty()) return {NAN, NAN};
  for (double x : ok) s.mean += x / ok.size();
  if (ok.size() > 1) {
    for (double x : ok) s.sd += (x - s.mean) * (x - s.mean);
    s.sd = std::sqrt(s.sd / (ok.size() - 1));
  }
  return s;
}

// The reference the study measures against, and a line saying what it is.
Image study_reference(const std::string& scene_path, const Scene& scene, const StudyOptions& o,
                      DeviceSet& devices, std::optional<Image> given, std::string& description) {
  if (given) {
    description = o.reference == kFurnaceReference ? "the analytic furnace" : o.reference;
    return *given;
  }
  // Cached next to the scene, remade when the scene file changed or the cache is shorter.
  fs::path scene_file(scene_path);
  fs::path cached = scene_file.parent_path() / (scene_file.stem().string() + ".reference.exr");
  double wanted =
      o.reference_seconds > 0 ? o.reference_seconds : 4 * o.seconds * o.integrators.size();
  std::error_code ec;
  if (fs::exists(cached, ec)) {
    ReferenceInfo info = read_reference_info(cached.string());
    if (info.scene_fingerprint == scene_fingerprint(scene_path) && info.seconds >= 0.99 * wanted) {
      description = cached.string() + " (cached: " + info.integrator + ", " +
                    std::to_string(info.seconds) + " s)";
      return read_exr(cached.string());
    }
  }
  ReferenceInfo info;
  Image ref = render_reference(devices, scene, wanted, 0x7e1f, info, o.show_progress);
  std::string where = cached.string();
  try {
    write_reference(cached.string(), ref, info);
  } catch (const Error&) {
    // The scene's folder is read-only. out_dir may be a staging folder renamed later: the
    // description names the file by its place in the output.
    write_reference((fs::path(o.out_dir) / "reference.exr").string(), ref, info);
    where = "reference.exr in the output folder";
  }
  description = where + " (" + info.integrator + ", " + std::to_string(info.seconds) + " s)";
  return ref;
}

void write_summary(const std::string& dir, const std::string& scene_path, const StudyOptions& o,
                   const StudyResult& r) {
  auto num = [](double v, int precision = 4) {
    if (!std::isfinite(v)) return std::string("");
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
  };
  const std::string csv = (fs::path(dir) / "summary.csv").string();
  write_atomically(csv, [&](const std::string& tmp) {
    write_stream_file(tmp, csv, [&](std::ostream& out) {
      out << "integrator,runs,seconds,final_rmse,final_rmse_sd,final_relmse,final_relmse_sd,slope_"
             "rmse,slope_rmse_sd,"
             "slope_relmse,slope_relmse_sd,target_rmse,time_to_target,reached_target,camera_paths_"
             "per_s,photons_per_s,"
             "startup_s\n";
      for (const IntegratorSummary& s : r.summaries)
        out << s.integrator << "," << s.runs << "," << o.seconds << "," << num(s.final_rmse, 6)
            << "," << num(s.final_rmse_sd, 6) << "," << num(s.final_relmse, 6) << ","
            << num(s.final_relmse_sd, 6) << "," << num(s.slope_rmse) << "," << num(s.slope_rmse_sd)
            << "," << num(s.slope_relmse) << "," << num(s.slope_relmse_sd) << ","
            << num(r.target, 6) << "," << (s.time_to_target >= 0 ? num(s.time_to_target) : "")
            << "," << s.reached_target << "," << num(s.camera_paths_per_second) << ","
            << num(s.photons_per_second) << "," << num(s.startup) << "\n";
    });
  });
  const std::string md = (fs::path(dir) / "summary.md").string();
  write_atomically(md, [&](const std::string& tmp) {
    write_stream_file(tmp, md, [&](std::ostream& out) {
      // File names are input bytes, and converge prints this file: escaped like a message.
      out << "Scene `" << printable(scene_path) << "`, " << o.seconds << " s per integrator, "
          << o.repeats
          << " run(s) each (mean ± sd), reference: " << printable(r.reference_description)
          << ".\n\n";
      out << "| integrator | final RMSE | final relMSE | RMSE slope | relMSE slope | time to RMSE "
          << num(r.target)
          << " (s) | camera paths/s | photons/s |\n|---|---|---|---|---|---|---|---|\n";
      auto pm = [&](double m, double sd, int p) {
        return num(m, p) + (o.repeats > 1 ? " ± " + num(sd, 2) : "");
      };
      for (const IntegratorSummary& s : r.summaries)
        out << "| " << s.integrator << " | " << pm(s.final_rmse, s.final_rmse_sd, 4) << " | "
            << pm(s.final_relmse, s.final_relmse_sd, 4) << " | "
            << pm(s.slope_rmse, s.slope_rmse_sd, 3) << " | "
            << pm(s.slope_relmse, s.slope_relmse_sd, 3) << " | "
            << (s.time_to_target >= 0 ? num(s.time_to_target, 3) : "not reached") << " | "
            << num(s.camera_paths_per_second, 3) << " | " << num(s.photons_per_second, 3) << " |\n";
      out << "\nSlopes are least-squares fits of log error over log seconds after the first "
          << kSlopeFitFrom * 100
          << " % of the budget, with the first pass's one-time start-up (kernel "
             "compilation at first launch) taken off the times; theory: −1/2 (RMSE) and −1 "
             "(relMSE) "
             "for unbiased "
             "estimators; for progressive photon mapping −α/2 and −α where its bias is nil (a "
             "furnace), down to −(1 − α) and −2(1 − α) where bias dominates (α = --alpha, "
             "default 0.8).\n";
    });
  });
}

}  // namespace

// The study's options that no parser checked (a library caller's as much as the CLI's).
static void check_study(const StudyOptions& o) {
  const std::vector<std::string> physical = IntegratorRegistry::names(true);
  std::string known;
  for (const std::string& name : physical) known += (known.empty() ? "" : ", ") + name;
  if (o.integrators.empty()) throw Error("--integrators: give at least one of " + known);
  for (const std::string& name : o.integrators)
    if (std::find(physical.begin(), physical.end(), name) == physical.end())
      throw Error("--integrators: unknown integrator \"" + name + "\" (" + known + ")");
  if (!(o.seconds > 0) && o.passes <= 0) throw Error("--time must be positive");
  if (o.repeats < 1) throw Error("--repeats must be at least 1");
}

StudyResult run_convergence_study(const std::string& scene_path, const StudyOptions& o) {
  check_study(o);
  check_directory(o.out_dir);
  Scene scene = load_scene(scene_path);
  // A reference that cannot exist is refused before the device is touched.
  std::optional<Image> given = reference_for(o.reference, scene, false);
  DeviceSet devices(o.device);
  StudyResult result;
  Image reference = study_reference(scene_path, scene, o, devices, std::move(given),
                                    result.reference_description);
  const std::vector<RenderLane> lanes = devices.upload(scene);

  std::vector<std::vector<std::vector<LogRow>>> by_integrator(o.integrators.size());
  std::vector<Image> finals;
  for (size_t k = 0; k < o.integrators.size(); ++k) {
    for (int run = 0; run < o.repeats; ++run) {
      IntegratorSettings settings = o.settings;
      settings.seed = o.settings.seed + run;
      RenderJob job(lanes, scene, o.integrators[k], settings, false);
      Film& film = job.film();
      ConvergenceLog log(reference);
      RenderOptions ro;
      ro.stop = o.passes > 0 ? StopCondition{0, o.passes} : StopCondition{o.seconds, 0};
      ro.observer = &log;
      ro.show_progress = o.show_progress;
      RenderSummary summary = job.run(ro);
      write_convergence_log((fs::path(o.out_dir) /
                             ("log_" + o.integrators[k] + "_" + std::to_string(run + 1) + ".csv"))
                                .string(),
                            log.rows());
      by_integrator[k].push_back(log.rows());
      if (run == 0) {
        Image img = film.image();
        write_exr((fs::path(o.out_dir) / (o.integrators[k] + ".exr")).string(), img);
        finals.push_back(img);
      }
      if (summary.interrupted) throw Error("converge: interrupted");
    }
  }

  // The target: given, or the worst final RMSE, which every integrator reaches.
  result.target = o.target;
  if (result.target < 0) {
    result.target = 0;
    for (const auto& runs : by_integrator)
      for (const auto& log : runs) result.target = std::max(result.target, log.back().rmse);
  }
  for (size_t k = 0; k < o.integrators.size(); ++k) {
    IntegratorSummary s;
    s.integrator = o.integrators[k];
    s.runs = o.repeats;
    std::vector<double> rmse, relmse, slope, slope_rel, reach, paths, photons, startup;
    for (const auto& log : by_integrator[k]) {
      const LogRow& last = log.back();
      rmse.push_back(last.rmse);
      relmse.push_back(last.relmse);
      std::vector<LogRow> fit = without_startup(log);
      startup.push_back(startup_seconds(log));
      const double budget = o.passes > 0 ? last.seconds : o.seconds;
      slope.push_back(loglog_slope(fit, false, kSlopeFitFrom * budget));
      slope_rel.push_back(loglog_slope(fit, true, kSlopeFitFrom * budget));
      double t = time_to_reach(log, result.target);
      if (t >= 0) reach.push_back(t), ++s.reached_target;
      paths.push_back(last.camera_paths / last.seconds);
      photons.push_back(last.photons / last.seconds);
    }
    Stats a = stats(rmse), b = stats(relmse), c = stats(slope), d = stats(slope_rel);
    s.final_rmse = a.mean, s.final_rmse_sd = a.sd, s.final_relmse = b.mean,
    s.final_relmse_sd = b.sd;
    s.slope_rmse = c.mean, s.slope_rmse_sd = c.sd, s.slope_relmse = d.mean,
    s.slope_relmse_sd = d.sd;
    s.time_to_target = reach.empty() ? -1 : stats(reach).mean;
    s.camera_paths_per_second = stats(paths).mean;
    s.photons_per_second = stats(photons).mean;
    s.startup = stats(startup).mean;
    result.summaries.push_back(s);
  }
  write_summary(o.out_dir, scene_path, o, result);

  // The final images side by side, one exposure for all.
  Image row;
  row.width = scene.camera.width * static_cast<int>(finals.size());
  row.height = scene.camera.height;
  row.xyz.assign(3 * row.pixels(), 0.0f);
  for (size_t k = 0; k < finals.size(); ++k)
    for (int y = 0; y < row.height; ++y)
      for (int x = 0; x < scene.camera.width; ++x)
        for (int c = 0; c < 3; ++c)
          row.xyz[3 * (static_cast<size_t>(y) * row.width + k * scene.camera.width + x) + c] =
              finals[k].xyz[3 * (static_cast<size_t>(y) * scene.camera.width + x) + c];
  write_png_preview((fs::path(o.out_dir) / "images.png").string(), row);

  if (o.plot) {
    run_embedded_python("plot_convergence.py", {o.out_dir}, "converge");
  }
  return result;
}

}  // namespace kasha
