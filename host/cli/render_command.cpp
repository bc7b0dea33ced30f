#include "cli/render_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "core/interrupt.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "render/debug_integrator.h"
#include "render/furnace.h"
#include "render/integrator_factory.h"
#include "render/photon_map_integrator.h"
#include "render/progressive_render.h"

namespace kasha {

static void check_writable(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throw Error(option + " " + path + ": directory " + dir.string() + " does not exist");
}

int run_render(const RenderArgs& a) {
  install_interrupt_handler();  // from the start, so an early Ctrl-C still gets one pass written
  check_writable(a.output, "-o");
  check_writable(a.png, "--png");
  check_writable(a.log, "--log");
  if (a.passes <= 0 && a.seconds <= 0) throw Error("render: give --time SECONDS or --passes N");
  if (a.view_given && a.integrator != "debug")
    throw Error("--view applies to --integrator debug only");
  Scene scene = load_scene(a.scene);
  RenderOptions options;
  options.stop = {a.seconds, a.passes};
  options.log_path = a.log;
  if (a.reference == "furnace") {
    Furnace f = analyze_furnace(scene);
    if (!f.qualifies)
      throw Error("--reference furnace: " + a.scene + " is not an analytic furnace: " + f.why_not);
    options.reference = furnace_image(scene, f.radiance, a.spectral);
  } else if (!a.reference.empty()) {
    options.reference = read_exr(a.reference);
  }
  ClContext cl(a.device);
  DeviceScene device_scene(cl, scene);
  Film film(scene.camera.width, scene.camera.height, scene.grid, a.spectral);
  std::unique_ptr<Integrator> integrator;
  if (a.integrator == "debug")
    integrator = std::make_unique<DebugIntegrator>(cl, scene, device_scene, film,
                                                   parse_debug_view(a.view), a.spp, a.seed);
  else
    integrator = make_integrator(
        a.integrator, cl, scene, device_scene, film,
        IntegratorSettings{a.spp, a.photons, a.alpha, a.radius, a.seed, a.edge_correction});
  RenderSummary summary = render_progressive(*integrator, film, options);
  Image image = film.image();
  write_exr(a.output, image);
  if (!a.png.empty()) write_png_preview(a.png, image);
  std::fprintf(stderr, "wrote %s%s%s: %d passes, %lld samples per pixel, %.2f s on %s\n",
               a.output.c_str(), a.png.empty() ? "" : " and ", a.png.c_str(), summary.passes,
               film.samples_per_pixel(), summary.seconds, cl.info().name.c_str());
  if (auto* pm = dynamic_cast<PhotonMapIntegrator*>(integrator.get())) {
    const PhotonMapTimes& t = pm->times();
    double total = t.photon_tracing + t.kd_tree + t.camera_pass + t.gather;
    if (total > 0)
      std::fprintf(stderr,
                   "photon mapping time: photon tracing %.0f %%, kd-tree %.0f %%, camera pass %.0f "
                   "%%, gather %.0f %%\n",
                   100 * t.photon_tracing / total, 100 * t.kd_tree / total,
                   100 * t.camera_pass / total, 100 * t.gather / total);
  }
  if (integrator->rejected_samples() > 0)
    std::fprintf(stderr, "kasha: warning: %lld samples were not finite and were left out\n",
                 integrator->rejected_samples());
  return summary.interrupted ? 130 : 0;
}

}  // namespace kasha
