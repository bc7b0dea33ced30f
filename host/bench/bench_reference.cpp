#include "bench/bench_reference.h"

#include <filesystem>

#include "core/error.h"
#include "image/exr_io.h"
#include "study/furnace.h"
#include "study/image_error.h"
#include "study/reference_image.h"

namespace kasha {

namespace fs = std::filesystem;

LoadedBenchScene load_bench_scene(const BenchScene& bench, const std::string& scenes_dir) {
  LoadedBenchScene s;
  s.bench = &bench;
  s.path = (fs::path(scenes_dir) / bench.file).string();
  if (bench.reference != "furnace")
    s.reference_path = (fs::path(scenes_dir) / bench.reference).string();
  s.scene = load_scene(s.path);
  // The same view at the bench resolution: fov_deg spans the shorter side either way.
  s.scene.camera.width = bench.width;
  s.scene.camera.height = bench.height;
  s.triangles = s.scene.triangles.size();
  return s;
}

void load_bench_reference(LoadedBenchScene& s) {
  const int w = s.bench->width, h = s.bench->height;
  if (s.bench->reference == "furnace") {
    Furnace f = analyze_furnace(s.scene);
    if (!f.qualifies) throw Error(s.path + ": not an analytic furnace: " + f.why_not);
    s.reference = furnace_image(s.scene, f.radiance, false);
    s.reference_description = "the analytic furnace";
    return;
  }
  const std::string remake = "; remake it with `kasha bench --make-references SECONDS` (README)";
  if (!fs::exists(s.reference_path))
    throw Error(s.reference_path + ": no such file (the reference of " + s.path + ")" + remake);
  ReferenceInfo info = read_reference_info(s.reference_path);
  const std::string fingerprint = scene_fingerprint(s.path);
  if (info.scene_fingerprint != fingerprint)
    throw Error(s.reference_path + ": made for another version of " + s.path +
                " (scene fingerprint " +
                (info.scene_fingerprint.empty() ? "none" : info.scene_fingerprint) +
                ", the file's " + fingerprint + ")" + remake);
  s.reference = read_exr(s.reference_path);
  if (s.reference.width != w || s.reference.height != h)
    throw Error(s.reference_path + ": " + std::to_string(s.reference.width) + "x" +
                std::to_string(s.reference.height) + ", but bench renders " + s.path + " at " +
                std::to_string(w) + "x" + std::to_string(h) + remake);
  char what[200];
  std::snprintf(what, sizeof what, "%s (%s, %.0f s, %lld samples per pixel)",
                s.reference_path.c_str(), info.integrator.c_str(), info.seconds,
                info.samples_per_pixel);
  s.reference_description = what;
}

}  // namespace kasha
