// kasha: the command line of DESIGN §5.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/measure_command.h"
#include "cli/render_command.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "opencl/device.h"
#include "render/convergence_study.h"
#include "render/device_scene.h"
#include "render/photon_map_integrator.h"
#include "render/reference_image.h"
#include "scene/scene.h"

using namespace kasha;

namespace {

int run_devices() {
  for (const DeviceInfo& d : list_devices()) {
    std::printf("%d: %s — %s [%s, %s, %u compute units, %.1f GiB]\n", d.index, d.platform.c_str(),
                d.name.c_str(), d.type.c_str(), d.version.c_str(), d.compute_units,
                d.global_mem_bytes / 1073741824.0);
  }
  return 0;
}

std::string bytes_text(double b) {
  char t[64];
  if (b >= 1 << 30)
    std::snprintf(t, sizeof t, "%.2f GiB", b / (1 << 30));
  else if (b >= 1 << 20)
    std::snprintf(t, sizeof t, "%.2f MiB", b / (1 << 20));
  else if (b >= 1 << 10)
    std::snprintf(t, sizeof t, "%.1f KiB", b / (1 << 10));
  else
    std::snprintf(t, sizeof t, "%.0f B", b);
  return t;
}

int run_info(const std::string& scene_path, bool spectral) {
  Scene scene = load_scene(scene_path);
  KernelSceneData data(scene);
  int emitting_triangles = 0;
  for (const Emitter& e : scene.emitters) emitting_triangles += e.triangle_count;
  std::printf("scene: %s\n", scene_path.c_str());
  std::printf("wavelengths: %s\n", scene.grid.describe().c_str());
  std::printf("features: fluorescence %s, gloss %s\n", scene.fluorescent() ? "yes" : "no",
              scene.glossy() ? "yes" : "no");
  std::printf("materials: %zu; shapes: %zu; triangles: %zu; emitters: %zu (%d triangles)\n",
              scene.materials.size(), scene.shapes.size(), scene.triangles.size(),
              scene.emitters.size(), emitting_triangles);
  std::printf("bvh: %zu nodes, depth %d (Embree SAH)\n", data.bvh.nodes.size(), data.bvh.depth);
  std::printf("camera: %dx%d, fov %g deg\n", scene.camera.width, scene.camera.height,
              scene.camera.fov_deg);
  std::printf("kernel build options: %s\n", build_options(scene_defines(scene, spectral)).c_str());
  size_t rows_count = spectral ? scene.grid.bins : 3;
  std::printf(
      "photon mapping: %zu bytes per photon (position, normal, %d bins); %zu bytes per visible "
      "point "
      "(geometry 8 values%s)\n",
      photon_record_bytes(scene), scene.grid.bins, visible_point_bytes(scene, spectral),
      scene.fluorescent()
          ? (", K = C∘d + c bᵀ: 2N + R = " + std::to_string(2 * scene.grid.bins + rows_count) +
             " values")
                .c_str()
          : (", K = C∘d: N = " + std::to_string(scene.grid.bins) + " values").c_str());
  size_t pixels = static_cast<size_t>(scene.camera.width) * scene.camera.height;
  size_t rows = spectral ? scene.grid.bins : 3;
  std::printf(
      "memory: scene %s (bvh %s, triangles %s, materials and spectra %s); film %s on the device, "
      "%s on the host\n",
      bytes_text(data.bytes()).c_str(),
      bytes_text(data.bvh.nodes.size() * sizeof(KBvhNode)).c_str(),
      bytes_text(data.bvh.triangles.size() * sizeof(KTriangle)).c_str(),
      bytes_text(data.materials.size() * sizeof(KMaterial) +
                 (data.spectra.size() + data.emitter_radiance.size()) * sizeof(float))
          .c_str(),
      bytes_text(pixels * rows * sizeof(float)).c_str(),
      bytes_text(pixels * rows * sizeof(double)).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kasha: a spectral renderer for fluorescent materials"};
  app.require_subcommand(1);

  app.add_subcommand("devices", "list OpenCL platforms and devices");

  std::string info_scene;
  bool info_spectral = false;
  CLI::App* info = app.add_subcommand(
      "info", "what a scene needs: bins, features, memory, kernel build options");
  info->add_option("scene", info_scene, "scene JSON file")->required();
  info->add_flag("--spectral", info_spectral, "report for a spectral film");

  RenderArgs r;
  CLI::App* render = app.add_subcommand("render", "render a scene to an EXR");
  render->add_option("scene", r.scene, "scene JSON file")->required();
  render->add_option("-o,--output", r.output, "output EXR")->required();
  render->add_option("--integrator", r.integrator, "photon (default), backward, forward, or debug")
      ->check(CLI::IsMember({"photon", "backward", "forward", "debug"}));
  render->add_option("--view", r.view, "debug view: emission, normals or albedo")
      ->check(CLI::IsMember({"emission", "normals", "albedo"}));
  render->add_option("--time", r.seconds, "stop after this many seconds")
      ->check(CLI::PositiveNumber);
  render->add_option("--passes", r.passes, "stop after this many passes")
      ->check(CLI::PositiveNumber);
  render->add_option("--spp", r.spp, "camera samples per pixel per pass")
      ->check(CLI::Range(1, 1 << 20));
  render->add_option("--alpha", r.alpha, "photon mapping: radius reduction α (default 2/3)")
      ->check(CLI::Range(0.01, 0.99));
  render
      ->add_option("--radius", r.radius,
                   "photon mapping: initial gather radius (default: from the pixel footprint)")
      ->check(CLI::PositiveNumber);
  render->add_option("--photons", r.photons, "photons per pass (forward, photon)")
      ->check(CLI::Range(1LL, (1LL << 31) - 1));
  render->add_option("--seed", r.seed, "random seed");
  render->add_option("--device", r.device, "OpenCL device index (see `kasha devices`)")
      ->check(CLI::NonNegativeNumber);
  render->add_option("--png", r.png, "also write a tone-mapped sRGB PNG preview");
  render->add_flag("--spectral", r.spectral, "add one channel per wavelength bin to the EXR");
  render->add_option("--reference", r.reference,
                     "reference EXR for the convergence log's error columns");
  render->add_option("--log", r.log, "convergence log CSV, a row after every pass");

  MeasureArgs m;
  CLI::App* measure =
      app.add_subcommand("measure", "turn fluorimeter or bispectral data into a material file");
  measure->add_option("--sample", m.sample,
                      "sample excitation–emission matrix (CSV or JASCO export)");
  measure->add_option("--etalon", m.etalon,
                      "etalon (white diffuse reference) excitation–emission matrix");
  measure->add_option("--etalon-reflectance", m.etalon_reflectance,
                      "the etalon's reflectance spectrum (CSV)");
  measure->add_option("--sensitivity", m.sensitivity,
                      "detector relative spectral sensitivity C(λ) (CSV)");
  measure->add_option("--gloss", m.gloss, "goniometer CSV: theta_in_deg, theta_out_deg, brdf");
  measure
      ->add_option("--band-nm", m.band_nm,
                   "half-width of the near-diagonal band (default: from the etalon)")
      ->check(CLI::PositiveNumber);
  measure->add_option("--cone-deg", m.cone_deg, "gloss cone around the mirror direction")
      ->check(CLI::Range(0.1, 90.0));
  measure->add_option("--bispectral", m.bispectral,
                      "a measured bispectral (Donaldson) matrix instead");
  measure->add_option("-o,--output", m.output, "material JSON to write")->required();
  measure->add_option("--plots", m.plots, "write the method's figures (PNG) into this directory");
  measure->add_option("--name", m.name, "material name (default: the output file's stem)");
  measure->add_flag("--clip", m.clip, "clip an energy gain instead of failing, and record it");

  StudyOptions study;
  std::string converge_scene, integrators = "backward,forward,photon";
  CLI::App* converge =
      app.add_subcommand("converge", "error against run time for several integrators");
  converge->add_option("scene", converge_scene, "scene JSON file")->required();
  converge->add_option("--integrators", integrators, "comma-separated: backward,forward,photon");
  converge->add_option("--time", study.seconds, "rendering seconds per integrator and run")
      ->required();
  converge->add_option("--reference", study.reference,
                       "reference EXR or `furnace` (default: cached next to the scene)");
  converge->add_option("--reference-time", study.reference_seconds,
                       "seconds for a new cached reference (default 4 × time × integrators)");
  converge->add_option("--repeats", study.repeats,
                       "runs per integrator, seeds 1..K, for error bars");
  converge->add_option("--target", study.target,
                       "RMSE whose time to reach is reported (default: the worst final)");
  converge->add_option("--spp", study.settings.spp, "backward: camera samples per pixel per pass");
  converge->add_option("--photons", study.settings.photons, "forward, photon: photons per pass");
  converge->add_option("--device", study.device, "OpenCL device index");
  converge->add_option("-o,--output", study.out_dir, "directory for logs, plot, images and summary")
      ->required();

  std::string reference_scene, reference_out;
  double reference_seconds = 0;
  unsigned reference_seed = 1;
  int reference_device = 0;
  CLI::App* reference = app.add_subcommand(
      "reference", "render a reference image with the lowest-variance unbiased integrator");
  reference->add_option("scene", reference_scene, "scene JSON file")->required();
  reference->add_option("--time", reference_seconds, "rendering seconds")
      ->required()
      ->check(CLI::PositiveNumber);
  reference->add_option("--seed", reference_seed, "random seed");
  reference->add_option("--device", reference_device, "OpenCL device index");
  reference->add_option("-o,--output", reference_out, "reference EXR")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("devices")) return run_devices();
    if (app.got_subcommand("info")) return run_info(info_scene, info_spectral);
    if (app.got_subcommand("render")) {
      r.view_given = render->count("--view") > 0;
      return run_render(r);
    }
    if (app.got_subcommand("measure")) return run_measure(m);
    if (app.got_subcommand("converge")) {
      install_interrupt_handler();
      study.integrators.clear();
      std::stringstream list(integrators);
      for (std::string name; std::getline(list, name, ',');) study.integrators.push_back(name);
      StudyResult r = run_convergence_study(converge_scene, study);
      std::printf(
          "converge: reference %s; wrote "
          "%s/{summary.md,summary.csv,convergence.png,images.png,log_*.csv}\n",
          r.reference_description.c_str(), study.out_dir.c_str());
      std::ifstream summary(study.out_dir + "/summary.md");
      std::printf("%s", std::string(std::istreambuf_iterator<char>(summary), {}).c_str());
      return 0;
    }
    if (app.got_subcommand("reference")) {
      install_interrupt_handler();
      Scene scene = load_scene(reference_scene);
      ClContext cl(reference_device);
      ReferenceInfo info;
      Image image = render_reference(cl, scene, reference_seconds, reference_seed, info, true);
      write_reference(reference_out, image, info);
      std::fprintf(stderr, "wrote %s: %s, %.1f s, %lld samples per pixel\n", reference_out.c_str(),
                   info.integrator.c_str(), info.seconds, info.samples_per_pixel);
      return 0;
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "kasha: error: %s\n", e.what());
    return 1;
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "kasha: error: OpenCL: %s\n", cl_error_text(e).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kasha: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
