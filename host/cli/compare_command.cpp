// `kasha compare IMAGE.exr REFERENCE.exr [--scene SCENE.json] [--block N]`: the error of an image
// against a reference as the convergence log measures it; given the scene, with the pixels that see
// an emitter directly left out; given a block size, of the N x N block means (the bench's
// validation measure: it sees a bias or a low-frequency error that per-pixel noise hides).
#include <cstdio>
#include <memory>
#include <string>

#include "bench/bench_validation.h"
#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "core/error.h"
#include "image/exr_io.h"
#include "study/emitter_pixels.h"
#include "study/image_error.h"

namespace kasha {

// Everything is read and checked before the first character is printed, so an error is the only
// line. When every pixel sees an emitter, nothing is left without them: that is said in words
// (exit 0, the whole image's errors stand) rather than as an RMSE of 0 over no pixels.
static int run_compare(const std::string& image_path, const std::string& reference_path,
                       const std::string& scene_path, int block) {
  Image image = read_exr(image_path), reference = read_exr(reference_path);
  ImageError all = image_error(image, reference);
  std::string rest_text;
  if (!scene_path.empty()) {
    Scene scene = load_scene(scene_path);
    if (scene.camera.width != image.width || scene.camera.height != image.height)
      throw Error("--scene " + scene_path + ": its camera is " +
                  std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) +
                  " but the image is " + std::to_string(image.width) + "x" +
                  std::to_string(image.height));
    std::vector<bool> lamp = emitter_pixels(scene);
    size_t count = 0;
    for (bool b : lamp) count += b;
    ImageError rest = image_error(image, reference, lamp);
    char text[160];
    if (rest.pixels == 0)
      std::snprintf(text, sizeof text, " | all %zu pixels see an emitter: none left without them",
                    count);
    else
      std::snprintf(text, sizeof text,
                    " | without the %zu pixels that see an emitter: rmse %.6g relmse %.6g", count,
                    rest.rmse, rest.relmse);
    rest_text = text;
  }
  if (block > 0) {
    ImageError blocks =
        image_error(block_average(image, block), block_average(reference, block));
    char text[160];
    std::snprintf(text, sizeof text, " | %dx%d block means: rmse %.6g relmse %.6g", block, block,
                  blocks.rmse, blocks.relmse);
    rest_text += text;
  }
  std::printf("rmse %.6g relmse %.6g%s\n", all.rmse, all.relmse, rest_text.c_str());
  return 0;
}

static Command::Action declare_compare(CLI::App& app) {
  struct Args {
    std::string image, reference, scene;
    int block = 0;
  };
  auto a = std::make_shared<Args>();
  app.add_option("image", a->image, "EXR to measure")->required();
  app.add_option("reference", a->reference, "reference EXR")->required();
  app.add_option("--scene", a->scene,
                 "the scene: also report the error without the pixels that see an emitter");
  app.add_option("--block", a->block,
                 "also the error of the N x N block means (the bench validates with 16)")
      ->check(cli::integer_within(1, 1 << 16));
  return [a] { return run_compare(a->image, a->reference, a->scene, a->block); };
}

KASHA_REGISTER_COMMAND(compare, "compare", "error of an image against a reference", 10, false,
                       declare_compare);

}  // namespace kasha
