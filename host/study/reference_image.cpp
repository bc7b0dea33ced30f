#include "study/reference_image.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "render/device_scene.h"
#include "render/render_job.h"
#include "study/furnace.h"
#include "study/image_error.h"

namespace kasha {

std::string scene_fingerprint(const std::string& scene_path) {
  std::ifstream in(scene_path, std::ios::binary);
  if (!in) throw Error(scene_path + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  // FNV-1a, 64 bits: stable across runs and builds (std::hash is not).
  unsigned long long h = 1469598103934665603ULL;
  for (unsigned char c : text.str()) h = (h ^ c) * 1099511628211ULL;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", h);
  return hex;
}

std::optional<Image> reference_for(const std::string& reference, const Scene& scene,
                                   bool spectral) {
  if (reference.empty()) return std::nullopt;
  if (reference == kFurnaceReference) {
    Furnace f = analyze_furnace(scene);
    if (!f.qualifies)
      throw Error("--reference furnace: " + scene.file +
                  " is not an analytic furnace: " + f.why_not);
    return furnace_image(scene, f.radiance, spectral);
  }
  std::error_code ec;  // a name too long or a link loop is this option's error too
  if (!std::filesystem::exists(reference, ec))
    throw Error("--reference " + reference + ": " +
                (ec && ec != std::errc::no_such_file_or_directory ? error_words(ec)
                                                                  : std::string("no such file")));
  Image image = read_exr(reference);
  check_reference_size(image, scene.camera.width, scene.camera.height);
  return image;
}

Image render_reference(DeviceSet& devices, const Scene& scene, double seconds, unsigned seed,
                       ReferenceInfo& info, bool show_progress) {
  IntegratorSettings settings;
  settings.seed = seed;
  RenderJob job(devices.upload(scene), scene, IntegratorRegistry::reference(), settings, false);
  RenderOptions options;
  options.stop.seconds = seconds;
  options.show_progress = show_progress;
  RenderSummary summary = job.run(options);
  Film& film = job.film();
  info.integrator = job.integrator().name();
  info.seconds = summary.seconds;
  info.samples_per_pixel = film.samples_per_pixel();
  info.scene_fingerprint = scene_fingerprint(scene.file);
  return film.image();
}

void write_reference(const std::string& path, const Image& image, const ReferenceInfo& info) {
  write_exr(path, image,
            {{"kashaReferenceIntegrator", info.integrator},
             {"kashaReferenceSeconds", std::to_string(info.seconds)},
             {"kashaReferenceSamplesPerPixel", std::to_string(info.samples_per_pixel)},
             {"kashaSceneFingerprint", info.scene_fingerprint}});
}

ReferenceInfo read_reference_info(const std::string& path) {
  std::map<std::string, std::string> a = read_exr_attributes(path);
  ReferenceInfo info;
  if (!a.count("kashaReferenceIntegrator")) return info;
  info.integrator = a["kashaReferenceIntegrator"];
  info.seconds = std::stod(a["kashaReferenceSeconds"]);
  info.samples_per_pixel = std::stoll(a["kashaReferenceSamplesPerPixel"]);
  info.scene_fingerprint = a["kashaSceneFingerprint"];
  return info;
}

}  // namespace kasha
