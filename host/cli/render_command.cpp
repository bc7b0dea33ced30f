#include "cli/render_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_set.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "mpi/mpi_world.h"
#include "mpi/remote_ranks.h"
#include "mpi/render_server.h"
#include "render/render_job.h"
#include "shared_types.h"
#include "study/convergence_log.h"
#include "study/furnace.h"
#include "study/image_error.h"

namespace kasha {

int run_render(const RenderArgs& a) {
  install_interrupt_handler();  // from the start, so an early Ctrl-C still gets one pass written
  if (a.passes <= 0 && a.seconds <= 0) throw Error("render: give --time SECONDS or --passes N");
  IntegratorRegistry::check_options(a.integrator, a.integrator_options_given);
  OutputSet outputs;
  outputs.input(a.scene, "the scene file");
  if (a.reference != "furnace") outputs.input(a.reference, "the --reference image");
  outputs.file("-o", a.output);
  outputs.file("--png", a.png);
  outputs.file("--log", a.log);
  Scene scene = load_scene(a.scene, std::nullopt, a.lamp);
  outputs.inputs_read("the scene's material or data file");
  RenderOptions options;
  options.stop = {a.seconds, a.passes};
  options.keep_log = !a.log.empty();  // written below with the other outputs
  if (a.reference == "furnace") {
    Furnace f = analyze_furnace(scene);
    if (!f.qualifies)
      throw Error("--reference furnace: " + a.scene + " is not an analytic furnace: " + f.why_not);
    options.reference = furnace_image(scene, f.radiance, a.spectral);
  } else if (!a.reference.empty()) {
    options.reference = read_exr(a.reference);
    check_reference_size(*options.reference, scene.camera.width, scene.camera.height);
  }
  DeviceSet devices(a.device);
  std::vector<RenderLane> lanes = devices.upload(scene);
  // Under mpirun the other ranks' devices join as lanes, after this rank's own.
  std::unique_ptr<RemoteRanks> remote;
  if (MpiWorld::get().several())
    remote = std::make_unique<RemoteRanks>(a.integrator, render_fingerprint(a));
  RenderJob job(lanes, scene, a.integrator, a.settings, a.spectral,
                remote ? remote->lanes() : std::vector<Integrator*>{});
  std::vector<std::string> names;
  for (size_t d = 0; d < devices.size(); ++d) names.push_back(devices[d].info().name);
  std::string where = devices.names();
  if (remote) {
    for (const auto& lane : remote->devices()) names.push_back(lane->description());
    where += " and " + std::to_string(remote->devices().size()) + " devices of " +
             std::to_string(MpiWorld::get().size() - 1) + " more ranks";
  }
  RenderSummary summary = job.run(options);
  const Film& film = job.film();
  Image image = film.image();
  outputs.write(a.output, [&](const std::string& tmp) { write_exr(tmp, image); });
  if (!a.png.empty())
    outputs.write(a.png, [&](const std::string& tmp) { write_png_preview(tmp, image); });
  if (!a.log.empty())
    outputs.write(a.log, [&](const std::string& tmp) { write_convergence_log(tmp, summary.log); });
  outputs.commit();
  std::fprintf(stderr, "wrote %s%s%s: %d passes, %lld samples per pixel, %.2f s on %s\n",
               a.output.c_str(), a.png.empty() ? "" : " and ", a.png.c_str(), summary.passes,
               film.samples_per_pixel(), summary.seconds, where.c_str());
  // Where a pass's time went, for integrators that time their stages ("time: <stage> (s)").
  double total = 0;
  std::string shares;
  for (const auto& [name, value] : film.tallies())
    if (name.rfind("time: ", 0) == 0) total += value;
  for (const auto& [name, value] : film.tallies())
    if (name.rfind("time: ", 0) == 0 && total > 0)
      shares += (shares.empty() ? "" : ", ") + name.substr(6, name.size() - 10) + " " +
                std::to_string(static_cast<int>(std::lround(100 * value / total))) + " %";
  if (!shares.empty()) std::fprintf(stderr, "%s time: %s\n", a.integrator.c_str(), shares.c_str());
  if (job.devices() > 1) {
    double work = 0;
    for (size_t d = 0; d < job.devices(); ++d) work += film.tally(device_work_tally(d));
    std::string each;
    for (size_t d = 0; d < job.devices(); ++d)
      each += (d ? ", " : "") + std::to_string(d) + " (" + names[d] + ") " +
              std::to_string(static_cast<int>(
                  std::lround(100 * film.tally(device_work_tally(d)) / std::max(work, 1e-300)))) +
              " %";
    std::fprintf(stderr, "work per device: %s\n", each.c_str());
  }
  double cut_share = 0;
  for (auto [cut, of] : {std::pair{kDepthGuardCut, kDepthGuardOf},
                         std::pair{kCameraDepthGuardCut, kCameraDepthGuardOf}})
    if (film.tally(of) > 0) cut_share = std::max(cut_share, film.tally(cut) / film.tally(of));
  if (cut_share > 1e-4)
    std::fprintf(
        stderr,
        "kasha: warning: paths reaching the %d-vertex depth guard were cut still carrying %.3g "
        "of the weight they started with; the image lacks what they would have added (too "
        "dark: the scene keeps nearly all its light)\n",
        a.settings.max_depth, cut_share);
  if (film.tally("rejected samples") > 0)
    std::fprintf(stderr, "kasha: warning: %.0f samples were not finite and were left out\n",
                 film.tally("rejected samples"));
  return summary.interrupted ? 130 : 0;
}

}  // namespace kasha
