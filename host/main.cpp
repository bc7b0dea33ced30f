// kasha: the command line of docs/commands.md
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/bench_command.h"
#include "cli/colorimetry_command.h"
#include "cli/command_line_errors.h"
#include "cli/compare_command.h"
#include "cli/converge_command.h"
#include "cli/delta_e_command.h"
#include "cli/info_command.h"
#include "cli/measure_command.h"
#include "cli/preview_command.h"
#include "cli/regions_command.h"
#include "cli/render_command.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "mpi/mpi_world.h"
#include "mpi/render_server.h"
#include "opencl/device.h"

using namespace kasha;
using namespace kasha::cli;

// Seconds beyond this would overflow the steady clock's deadline (nanoseconds in 64 bits).
constexpr double kMaxSeconds = 1e9;
constexpr long long kMaxInt = 2147483647;
constexpr const char* kDeviceHelp =
    "OpenCL devices: an index, a comma-separated list (0,1; an index named twice gives its "
    "device a second queue) or all; see `kasha devices`";

// The options of IntegratorSettings, each read by the integrators that list it in the registry.
static void add_integrator_options(CLI::App* app, IntegratorSettings& s) {
  app->add_option("--spp", s.spp,
                  "camera samples per pixel per pass (default 16; photon mapping 8)")
      ->check(integer_within(1, 1 << 20));
  app->add_option("--photons", s.photons, "photons per pass")->check(integer_within(1, kMaxInt));
  app->add_option("--alpha", s.alpha, "photon mapping: radius reduction α (default 0.8)")
      ->check(number_within(0.01, 0.99));
  app->add_option("--radius", s.radius,
                  "photon mapping: initial gather radius (default: from the pixel footprint)")
      ->check(positive_number());
  app->add_flag("--edge-correction", s.edge_correction,
                "photon mapping: divide the density by the measured fraction of the gather discs "
                "on accepted surface (default; --edge-correction=false leaves it out)");
  app->add_option("--gather", s.gather,
                  "photon mapping: gather on the device (a hashed grid) or on the host "
                  "(nanoflann); default auto: the device")
      ->check(one_of({"auto", "device", "host"}));
  app->add_option("--memory", s.memory,
                  "photon mapping: memory for the photon store, bytes with an optional unit "
                  "(512MiB, 2GB); default: a quarter of the device's memory (an eighth on a CPU)")
      ->transform(byte_size())
      ->check(integer_within(1, 1LL << 50));
  app->add_option("--view", s.view, "debug view: emission, normals or albedo")
      ->check(one_of({"emission", "normals", "albedo"}));
}

static int report_interrupt() {
  std::fprintf(stderr, "kasha: interrupted\n");
  return kInterruptExitCode;
}

// Input and run errors: exit 1. A failure after a signal (a device call or a compiler cut short)
// is the interrupt's doing: that is what is reported.
static int report_error(const std::string& message) {
  if (interrupt_requested()) return report_interrupt();
  std::fprintf(stderr, "kasha: error: %s\n", one_line(message).c_str());
  return 1;
}

// The command line of this process; under MPI, ranks > 0 serve rank 0's render instead (or wait
// for its end: other commands run on rank 0 alone).
static int run(int argc, char** argv, const MpiWorld& world) {
  CLI::App app{"kasha: a spectral renderer for fluorescent materials"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "kasha " KASHA_VERSION);

  app.add_subcommand("devices", "list OpenCL platforms and devices");

  std::string info_scene, info_lamp;
  bool info_spectral = false;
  CLI::App* info = app.add_subcommand(
      "info", "what a scene needs: bins, features, memory, kernel build options");
  info->add_option("scene", info_scene, "scene JSON file")->required();
  info->add_flag("--spectral", info_spectral, "report for a spectral film");
  info->add_option("--lamp", info_lamp, "switch on this one of the scene's \"lamps\"");

  RenderArgs r;
  CLI::App* render = app.add_subcommand("render", "render a scene to an EXR");
  render->add_option("scene", r.scene, "scene JSON file")->required();
  render->add_option("-o,--output", r.output, "output EXR")->required();
  std::string integrator_help = "the integrator (default " + std::string(kDefaultIntegrator) + "):";
  for (const IntegratorInfo& info : IntegratorRegistry::all())
    integrator_help += "\n  " + info.name + ": " + info.description;
  render->add_option("--integrator", r.integrator, integrator_help)
      ->check(one_of(IntegratorRegistry::names(false)));
  // Both may be given: the render stops at whichever comes first.
  render->add_option("--time", r.seconds, "stop after this many seconds")
      ->check(positive_number(kMaxSeconds));
  render->add_option("--passes", r.passes, "stop after this many passes")
      ->check(integer_within(1, kMaxInt));
  add_integrator_options(render, r.settings);
  render->add_option("--seed", r.settings.seed, "random seed")
      ->check(integer_within(0, 4294967295LL));
  render
      ->add_option("--max-depth", r.settings.max_depth,
                   "safety limit on path length in vertices (default 262144, far beyond what "
                   "Russian roulette reaches); what it cuts is reported")
      ->check(integer_within(1, 1 << 30));
  render
      ->add_option("--sampler", r.settings.sampler,
                   "sobol (default: Owen-scrambled Sobol points) or independent (PCG streams)")
      ->check(one_of({"sobol", "independent"}));
  render->add_option("--device", r.device, kDeviceHelp)->check(device_list());
  render->add_option("--lamp", r.lamp, "switch on this one of the scene's \"lamps\"");
  render->add_option("--png", r.png, "also write a tone-mapped sRGB PNG preview");
  render->add_flag("--spectral", r.spectral, "add one channel per wavelength bin to the EXR");
  render->add_option("--reference", r.reference,
                     "reference EXR for the convergence log's error columns");
  render->add_option("--log", r.log, "convergence log CSV, a row after every pass");
  // Usage errors found after the parse, still reported as usage errors (exit 2).
  render->callback([&] {
    if (r.seconds <= 0 && r.passes <= 0)
      throw CLI::ValidationError("render", "give --time SECONDS or --passes N");
    for (const std::string& option : IntegratorRegistry::options())
      if (render->count(option) > 0) r.integrator_options_given.push_back(option);
    try {
      IntegratorRegistry::check_options(r.integrator, r.integrator_options_given);
    } catch (const Error& e) {
      throw CLI::ValidationError(e.what());  // already `--OPTION: what`
    }
  });

  MeasureArgs m;
  CLI::App* measure =
      app.add_subcommand("measure", "turn fluorimeter or bispectral data into a material file");
  CLI::Option* sample = measure->add_option(
      "--sample", m.sample, "sample excitation–emission matrix (CSV or JASCO export)");
  CLI::Option* etalon = measure->add_option(
      "--etalon", m.etalon, "etalon (white diffuse reference) excitation–emission matrix");
  CLI::Option* etalon_reflectance = measure->add_option(
      "--etalon-reflectance", m.etalon_reflectance, "the etalon's reflectance spectrum (CSV)");
  CLI::Option* sensitivity = measure->add_option(
      "--sensitivity", m.sensitivity, "detector relative spectral sensitivity C(λ) (CSV)");
  measure->add_option("--gloss", m.gloss, "goniometer CSV: theta_in_deg, theta_out_deg, brdf");
  measure
      ->add_option("--band-nm", m.band_nm,
                   "half-width of the near-diagonal band (default: from the etalon)")
      ->check(positive_number(1000));
  measure->add_option("--cone-deg", m.cone_deg, "gloss cone around the mirror direction")
      ->check(number_within(0.1, 90.0));
  measure
      ->add_option("--bispectral", m.bispectral, "a measured bispectral (Donaldson) matrix instead")
      ->excludes(sample)
      ->excludes(etalon)
      ->excludes(etalon_reflectance)
      ->excludes(sensitivity);
  measure->add_option("-o,--output", m.output, "material JSON to write")->required();
  measure->add_option("--plots", m.plots, "write the method's figures (PNG) into this directory");
  measure->add_option("--name", m.name, "material name (default: the output file's stem)")
      ->check(utf8_text());
  measure->add_flag("--clip", m.clip, "clip an energy gain instead of failing, and record it");
  measure->callback([&] {
    if (m.bispectral.empty() &&
        (m.sample.empty() || m.etalon.empty() || m.etalon_reflectance.empty()))
      throw CLI::ValidationError(
          "measure", "give --sample, --etalon and --etalon-reflectance (or --bispectral)");
  });

  ColorimetryArgs col;
  CLI::App* colorimetry = app.add_subcommand(
      "colorimetry",
      "a material's total radiance factor, XYZ, CIELAB and CIE whiteness/tint under illuminants");
  colorimetry->add_option("material", col.material, "material JSON file")->required();
  colorimetry->add_option(
      "--illuminant", col.illuminants,
      "a spectrum: built-in name (D65, A, F11, …), CSV file or JSON value; repeat for a table "
      "(default D65)");
  colorimetry->add_option("--observer", col.observer, "CIE 1931 2° or CIE 1964 10° (default 2)")
      ->check(one_of({"2", "10"}));
  colorimetry->add_option("--bin-nm", col.bin_nm, "wavelength bin width (default 10)")
      ->check(number_within(0.1, 100.0));
  colorimetry->add_option("--as-is", col.as_is,
                          "compare with the material taken \"as is\": its radiance factor under "
                          "this lamp as a plain reflectance (ΔE2000 per illuminant)");
  colorimetry->add_option("--write-as-is", col.write_as_is,
                          "write that \"as is\" material as a material file");
  colorimetry->add_option("--json", col.json, "results as JSON");
  colorimetry->add_option("--csv", col.csv, "results as CSV, a row per illuminant");
  colorimetry->add_option("--plot", col.plot, "radiance factors as a PNG figure");

  std::string lab1, lab2;
  CLI::App* delta_e =
      app.add_subcommand("delta-e", "the CIEDE2000 colour difference between two CIELAB colours");
  delta_e->add_option("lab1", lab1, "L*,a*,b*")->required();
  delta_e->add_option("lab2", lab2, "L*,a*,b*")->required();

  std::string preview_exr, preview_png;
  double preview_scale = 0;
  CLI::App* preview = app.add_subcommand("preview", "an EXR as a tone-mapped sRGB PNG");
  preview->add_option("image", preview_exr, "EXR image")->required();
  preview->add_option("-o,--output", preview_png, "PNG to write")->required();
  preview
      ->add_option("--scale", preview_scale,
                   "multiply XYZ by this (Y = 1 is white) instead of exposing by the log-average "
                   "luminance")
      ->check(positive_number());

  RegionsArgs reg;
  CLI::App* regions = app.add_subcommand(
      "regions", "an image's mean XYZ over each shape of its scene, from pixels well inside it");
  regions->add_option("scene", reg.scene, "scene JSON file (its camera made the image)")
      ->required();
  regions->add_option("image", reg.image, "EXR image")->required();
  regions
      ->add_option("--margin", reg.margin_px,
                   "pixels count when the shape is also seen this many pixels around their centre "
                   "(default 1)")
      ->check(number_within(0, 1 << 20));
  regions->add_option("--white", reg.white,
                      "white-reference EXR (the samples replaced by a perfect white): adds XYZ "
                      "relative to it (Y = 100) and CIELAB");
  regions->add_option("--json", reg.json, "the regions as JSON");

  StudyOptions study;
  std::string converge_scene, integrators;
  CLI::App* converge =
      app.add_subcommand("converge", "error against run time for several integrators");
  converge->add_option("scene", converge_scene, "scene JSON file")->required();
  converge
      ->add_option("--integrators", integrators, "comma-separated (default: every physical one)")
      ->check(list_of(IntegratorRegistry::names(true), "integrator"));
  converge->add_option("--time", study.seconds, "rendering seconds per integrator and run")
      ->required()
      ->check(positive_number(kMaxSeconds));
  converge->add_option("--reference", study.reference,
                       "reference EXR or `furnace` (default: cached next to the scene)");
  converge
      ->add_option("--reference-time", study.reference_seconds,
                   "seconds for a new cached reference (default 4 × time × integrators)")
      ->check(positive_number(kMaxSeconds));
  converge
      ->add_option("--repeats", study.repeats, "runs per integrator, seeds 1..K, for error bars")
      ->check(integer_within(1, 1000));
  converge
      ->add_option("--target", study.target,
                   "RMSE whose time to reach is reported (default: the worst final)")
      ->check(positive_number());
  converge->add_option("--spp", study.settings.spp, "camera samples per pixel per pass")
      ->check(integer_within(1, 1 << 20));
  converge->add_option("--photons", study.settings.photons, "photons per pass")
      ->check(integer_within(1, kMaxInt));
  converge->add_option("--device", study.device, kDeviceHelp)->check(device_list());
  converge->add_option("--sampler", study.settings.sampler, "sobol (default) or independent")
      ->check(one_of({"sobol", "independent"}));
  converge->add_option("-o,--output", study.out_dir, "directory for logs, plot, images and summary")
      ->required();

  std::string compare_image, compare_reference, compare_scene;
  CLI::App* compare = app.add_subcommand("compare", "error of an image against a reference");
  compare->add_option("image", compare_image, "EXR to measure")->required();
  compare->add_option("reference", compare_reference, "reference EXR")->required();
  compare->add_option("--scene", compare_scene,
                      "the scene: also report the error without the pixels that see an emitter");

  std::string reference_scene, reference_out;
  double reference_seconds = 0;
  unsigned reference_seed = 1;
  std::string reference_device = "0";
  CLI::App* reference = app.add_subcommand(
      "reference", "render a reference image with the lowest-variance unbiased integrator");
  reference->add_option("scene", reference_scene, "scene JSON file")->required();
  reference->add_option("--time", reference_seconds, "rendering seconds")
      ->required()
      ->check(positive_number(kMaxSeconds));
  reference->add_option("--seed", reference_seed, "random seed")
      ->check(integer_within(0, 4294967295LL));
  reference->add_option("--device", reference_device, kDeviceHelp)->check(device_list());
  reference->add_option("-o,--output", reference_out, "reference EXR")->required();

  BenchArgs bench_args;
  bench_args.version = KASHA_VERSION;
  CLI::App* bench = app.add_subcommand(
      "bench",
      "fixed scenes × the physical integrators for a fixed time on each device: throughput, "
      "rays, time, memory, a validated image per run and a score per device");
  bench
      ->add_option("--device", bench_args.device,
                   "OpenCL device index, indices (0,1) or all, each benchmarked in turn "
                   "(default 0)")
      ->check(device_list());
  bench->add_option("--time", bench_args.seconds, "rendering seconds per run (default 10)")
      ->check(positive_number(kMaxSeconds));
  CLI::Option* bench_json = bench->add_option("--json", bench_args.json, "the record as JSON");
  bench->add_option("--scenes", bench_args.scenes,
                    "the folder holding the bench scenes and scenes/bench/ references (default: "
                    "the source tree's scenes/)");
  bench
      ->add_option("--make-references", bench_args.make_references,
                   "instead of benchmarking, render the bench scenes' reference images for this "
                   "many seconds each (the reference integrator, first listed device)")
      ->check(positive_number(kMaxSeconds))
      ->excludes(bench_json);

  require_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (world.rank() > 0 && e.get_exit_code() != 0)
      refuse_render("its command line: " + parse_error_line(app, e));
    return exit_for_parse_error(app, e);
  }
  const std::string command = app.get_subcommands().front()->get_name();
  if (world.rank() > 0) {
    if (command == "render") return serve_render(r);
    refuse_render("it runs kasha " + command + ", not render");
    return 0;
  }
  if (world.several() && command != "render")
    warn(command + " runs on rank 0 alone under MPI; " +
         (world.size() == 2 ? std::string("the other rank waits")
                            : "the other " + std::to_string(world.size() - 1) + " ranks wait") +
         " for it");
  try {
    if (app.got_subcommand("devices")) return run_devices();
    if (app.got_subcommand("info")) return run_info(info_scene, info_spectral, info_lamp);
    if (app.got_subcommand("render")) return run_render(r);
    if (app.got_subcommand("measure")) return run_measure(m);
    if (app.got_subcommand("colorimetry")) return run_colorimetry(col);
    if (app.got_subcommand("regions")) return run_regions(reg);
    if (app.got_subcommand("delta-e")) return run_delta_e(lab1, lab2);
    if (app.got_subcommand("preview")) return run_preview(preview_exr, preview_png, preview_scale);
    if (app.got_subcommand("converge")) return run_converge(converge_scene, integrators, study);
    if (app.got_subcommand("bench")) return run_bench_command(bench_args);
    if (app.got_subcommand("compare"))
      return run_compare(compare_image, compare_reference, compare_scene);
    if (app.got_subcommand("reference"))
      return run_reference(reference_scene, reference_seconds, reference_seed, reference_device,
                           reference_out);
  } catch (const Interrupted&) {
    return report_interrupt();
  } catch (const Error& e) {
    return report_error(e.what());
  } catch (const cl::Error& e) {
    return report_error("OpenCL: " + cl_error_text(e));
  } catch (const std::exception& e) {
    return report_error(e.what());
  }
  return 0;
}

int main(int argc, char** argv) {
  install_exit_on_interrupt();  // render, converge, reference and bench take over with their own
  std::unique_ptr<MpiWorld> world;
  try {
    world = std::make_unique<MpiWorld>(&argc, &argv);  // starts MPI only under mpirun
  } catch (const Error& e) {
    return report_error(e.what());
  }
  // Ranks > 0 end when rank 0 says so: a signal (mpirun's SIGTERM on Ctrl-C) only raises the flag
  // their work and rank 0's questions see (mpi/rank_control.h), lest they vanish unanswering.
  if (world->rank() > 0) install_interrupt_handler();
  const int code = run(argc, argv, *world);
  // Rank 0 speaks for the job: the other ranks' failures reached it in messages.
  if (!world->finalize()) return 1;
  return world->rank() == 0 ? code : 0;
}
