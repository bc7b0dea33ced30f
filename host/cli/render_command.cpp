// `kasha render`: a scene through one integrator to an EXR (and PNG), with progress, Ctrl-C, a
// convergence log and a reference. Under mpirun, rank 0 runs it with the other ranks' devices as
// lanes; the other ranks serve rank 0 (mpi/render_server.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "cli/render_options.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/output_set.h"
#include "core/warning.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "mpi/mpi_world.h"
#include "mpi/remote_ranks.h"
#include "mpi/render_server.h"
#include "render/depth_cap.h"
#include "render/render_job.h"
#include "render/render_spec.h"
#include "shared/shared_types.h"
#include "study/convergence_log.h"
#include "study/reference_image.h"

namespace kasha {

namespace {

struct RenderArgs {
  RenderSpec spec;
  std::string output, png, reference, log;
};

// What the render's passes went to: stage shares, devices' shares, the depth guard, rejections.
void report_render(const RenderArgs& a, const RenderJob& job,
                   const std::vector<std::string>& names) {
  const PassCounters& counters = job.film().counters();
  // Where a pass's time went, for integrators that time their stages.
  double total = 0;
  std::string shares;
  for (const StageTime& s : counters.stage_seconds) total += s.seconds;
  for (const StageTime& s : counters.stage_seconds)
    if (total > 0)
      shares += (shares.empty() ? "" : ", ") + s.stage + " " +
                std::to_string(static_cast<int>(std::lround(100 * s.seconds / total))) + " %";
  if (!shares.empty())
    std::fprintf(stderr, "%s time: %s\n", a.spec.integrator.c_str(), shares.c_str());
  if (job.devices() > 1) {
    double work = 0;
    for (size_t d = 0; d < job.devices(); ++d) work += counters.work_of(d);
    std::string each;
    for (size_t d = 0; d < job.devices(); ++d)
      each += (d ? ", " : "") + std::to_string(d) + " (" + names[d] + ") " +
              std::to_string(static_cast<int>(
                  std::lround(100 * counters.work_of(d) / std::max(work, 1e-300)))) +
              " %";
    std::fprintf(stderr, "work per device: %s\n", each.c_str());
  }
  double cut_share = 0;
  for (const DepthGuardTally& guard : {counters.depth_guard, counters.camera_depth_guard})
    if (guard.of > 0) cut_share = std::max(cut_share, guard.cut / guard.of);
  if (cut_share > 1e-4)
    std::fprintf(
        stderr,
        "kasha: warning: paths reaching the %d-vertex depth guard were cut still carrying %.3g "
        "of the weight they started with; the image lacks what they would have added (too "
        "dark: the scene keeps nearly all its light)\n",
        a.spec.settings.depth_guard, cut_share);
  if (counters.rejected_samples > 0)
    std::fprintf(stderr, "kasha: warning: %.0f samples were not finite and were left out\n",
                 counters.rejected_samples);
}

// What the integrator leaves out of this scene's image, or estimates short: one warning each.
void warn_what_it_cannot_see(const Scene& scene, const std::string& integrator) {
  const IntegratorTraits& traits = IntegratorRegistry::find(integrator).traits;
  if (scene.has_delta_surfaces() && !traits.sees_camera_mirrors)
    warn(
        integrator + ": ideal mirrors, glass and metal are out of its reach from a pinhole " +
        "camera and show black, as does a smooth coat's reflection (backward and photon see them)");
  if (scene.mixes_delta() && traits.physical && !traits.unbiased)
    warn(integrator + ": a mix with a smooth (delta) material stores photons on only its " +
         "other material's share of the surface, so merges there fall short (backward and bpt " +
         "are unbiased on it; docs/materials.md#mixes)");
  if (scene.partly_smooth_conductor() && traits.direct_by_merges)
    warn(integrator + ": a metal whose roughness texture is smooth at some points stores " +
         "photons on only its rough points, so merges near the smooth ones fall short " +
         "(backward and bpt are unbiased on it; docs/materials.md#rough-surfaces)");
  if (scene.has_light(LightType::infinite) && !traits.sees_camera_mirrors)
    warn(integrator + ": an infinite light seen directly by the camera is out of its reach " +
         "and shows black (backward and photon see it)");
}

int run_render(const RenderArgs& a) {
  install_interrupt_handler();  // from the start, so an early Ctrl-C still gets one pass written
  const RenderSpec& spec = a.spec;
  OutputSet outputs;
  outputs.input(spec.scene, "the scene file");
  if (a.reference != kFurnaceReference) outputs.input(a.reference, "the --reference image");
  outputs.file("-o", a.output);
  outputs.file("--png", a.png);
  outputs.file("--log", a.log);
  Scene scene = load_scene(spec.scene, spec.grid(), spec.lamp, spec.materials);
  outputs.inputs_read("the scene's material or data file");
  // `--max-depth scene` on a scene that names none: a usage error, found once the scene is read.
  if (const std::string refusal = depth_cap_refusal(spec.settings, scene); !refusal.empty()) {
    std::fprintf(stderr, "kasha: error: %s\n", refusal.c_str());
    return kUsageExitCode;
  }
  ConvergenceLog log(reference_for(a.reference, scene, spec.spectral));
  RenderOptions options;
  options.stop = spec.stop;
  if (!a.log.empty()) options.observer = &log;  // written below with the other outputs
  DeviceSet devices(spec.device);
  std::vector<RenderLane> lanes = devices.upload(scene);
  // Under mpirun the other ranks' devices join as lanes, after this rank's own.
  std::unique_ptr<RemoteRanks> remote;
  if (MpiWorld::get().several())
    remote = std::make_unique<RemoteRanks>(spec.integrator, render_fingerprint(spec));
  RenderJob job(lanes, scene, spec.integrator, spec.settings, spec.spectral,
                remote ? remote->lanes() : std::vector<Integrator*>{});
  warn_what_it_cannot_see(scene, spec.integrator);
  std::vector<std::string> names;
  for (size_t d = 0; d < devices.size(); ++d) names.push_back(devices[d].info().name);
  std::string where = devices.names();
  if (remote) {
    for (const auto& lane : remote->devices()) names.push_back(lane->description());
    where += " and " + std::to_string(remote->devices().size()) + " devices of " +
             std::to_string(MpiWorld::get().size() - 1) + " more ranks";
  }
  RenderSummary summary = job.run(options);
  // Under mpirun an interrupt may be its word that a rank died: that verdict (the rank named, no
  // image) comes before anything is written.
  MpiWorld::get().settle_interrupt();
  const Film& film = job.film();
  Image image = film.image();
  outputs.write(a.output, [&](const std::string& tmp) { write_exr(tmp, image); });
  if (!a.png.empty())
    outputs.write(a.png, [&](const std::string& tmp) { write_png_preview(tmp, image); });
  if (!a.log.empty())
    outputs.write(a.log, [&](const std::string& tmp) { write_convergence_log(tmp, log.rows()); });
  outputs.commit();
  std::fprintf(stderr, "wrote %s%s%s: %d passes, %lld samples per pixel, %.2f s on %s\n",
               a.output.c_str(), a.png.empty() ? "" : " and ", a.png.c_str(), summary.passes,
               film.samples_per_pixel(), summary.seconds, where.c_str());
  report_render(a, job, names);
  return summary.interrupted ? 130 : 0;
}

Command::Action declare(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  RenderSpec& r = a->spec;
  app.add_option("scene", r.scene, "scene: kasha JSON or pbrt-v4 (.pbrt)")->required();
  app.add_option("-o,--output", a->output, "output EXR")->required();
  std::string integrator_help = "the integrator (default " + std::string(kDefaultIntegrator) + "):";
  for (const IntegratorInfo& info : IntegratorRegistry::all())
    integrator_help += "\n  " + info.name + ": " + info.description;
  app.add_option("--integrator", r.integrator, integrator_help)
      ->check(cli::one_of(IntegratorRegistry::names(false)));
  // Both may be given: the render stops at whichever comes first.
  app.add_option("--time", r.stop.seconds, "stop after this many seconds")
      ->check(cli::positive_number(cli::kMaxSeconds));
  app.add_option("--passes", r.stop.passes, "stop after this many passes")
      ->check(cli::integer_within(1, 2147483647));
  cli::add_setting_options(app, r.settings);
  cli::add_device_option(app, r.device);
  app.add_option("--lamp", r.lamp, "switch on this one of the scene's \"lamps\"");
  cli::add_material_option(app, r.materials);
  cli::add_bin_option(app, r.bin_nm);
  app.add_option("--png", a->png, "also write a tone-mapped sRGB PNG preview");
  app.add_flag("--spectral", r.spectral, "add one channel per wavelength bin to the EXR");
  app.add_option("--reference", a->reference,
                 "reference EXR for the convergence log's error columns, or furnace");
  app.add_option("--log", a->log, "convergence log CSV, a row after every pass");
  // Usage errors found after the parse, still reported as usage errors (exit 2).
  app.callback([a, &app] {
    if (!a->spec.stop.given())
      throw CLI::ValidationError("render", "give --time SECONDS or --passes N");
    try {
      IntegratorRegistry::check_options(a->spec.integrator, cli::integrator_options_given(app));
    } catch (const Error& e) {
      throw CLI::ValidationError(e.what());  // already `--OPTION: what`
    }
  });
  return [a] { return MpiWorld::get().rank() > 0 ? serve_render(a->spec) : run_render(*a); };
}

}  // namespace

KASHA_REGISTER_COMMAND(render, "render", "render a scene to an EXR", 3, /*every rank*/ true,
                       declare);

}  // namespace kasha
