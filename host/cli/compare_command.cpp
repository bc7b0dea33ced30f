#include "cli/compare_command.h"

#include <cstdio>

#include "core/error.h"
#include "image/exr_io.h"
#include "study/emitter_pixels.h"
#include "study/image_error.h"

namespace kasha {

int run_compare(const std::string& image_path, const std::string& reference_path,
                const std::string& scene_path) {
  Image image = read_exr(image_path), reference = read_exr(reference_path);
  ImageError all = image_error(image, reference);
  std::printf("rmse %.6g relmse %.6g", all.rmse, all.relmse);
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
    std::printf(" | without the %zu pixels that see an emitter: rmse %.6g relmse %.6g", count,
                rest.rmse, rest.relmse);
  }
  std::printf("\n");
  return 0;
}

}  // namespace kasha
