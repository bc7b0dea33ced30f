// `kasha reference`: a reference image of a scene, rendered with the registry's reference
// integrator (the lowest-variance unbiased one) for a given time, with what made it recorded in
// the EXR's attributes (study/reference_image.h).
#include <cstdio>
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "cli/render_options.h"
#include "core/interrupt.h"
#include "core/output_set.h"
#include "render/device_set.h"
#include "study/reference_image.h"

namespace kasha {

static int run_reference(const std::string& scene_path, double seconds, unsigned seed,
                         const std::string& device, const std::string& out) {
  install_interrupt_handler();
  OutputSet outputs;
  outputs.input(scene_path, "the scene file");
  outputs.file("-o", out);
  Scene scene = load_scene(scene_path);
  outputs.inputs_read("the scene's material or data file");
  DeviceSet devices(device);
  ReferenceInfo info;
  Image image = render_reference(devices, scene, seconds, seed, info, true);
  outputs.write(out, [&](const std::string& tmp) { write_reference(tmp, image, info); });
  outputs.commit();
  std::fprintf(stderr, "wrote %s: %s, %.1f s, %lld samples per pixel\n", out.c_str(),
               info.integrator.c_str(), info.seconds, info.samples_per_pixel);
  return 0;
}

static Command::Action declare_reference(CLI::App& app) {
  struct Args {
    std::string scene, out, device = "0";
    double seconds = 0;
    unsigned seed = 1;
  };
  auto a = std::make_shared<Args>();
  app.add_option("scene", a->scene, "scene JSON file")->required();
  app.add_option("--time", a->seconds, "rendering seconds")
      ->required()
      ->check(cli::positive_number(cli::kMaxSeconds));
  app.add_option("--seed", a->seed, "random seed")->check(cli::integer_within(0, 4294967295LL));
  cli::add_device_option(app, a->device);
  app.add_option("-o,--output", a->out, "reference EXR")->required();
  return [a] { return run_reference(a->scene, a->seconds, a->seed, a->device, a->out); };
}

KASHA_REGISTER_COMMAND(reference, "reference",
                       "render a reference image with the lowest-variance unbiased integrator", 11,
                       false, declare_reference);

}  // namespace kasha
