// `kasha preview`: an EXR as a PNG preview, exposed by Reinhard's key or by a given scale (so that
// several images can share one exposure).
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "core/output_set.h"
#include "image/exr_io.h"
#include "image/png_preview.h"

namespace kasha {

static int run_preview(const std::string& exr, const std::string& png, double scale) {
  OutputSet outputs;
  outputs.input(exr, "the image");
  outputs.file("-o", png);
  Image image = read_exr(exr);
  outputs.write(png, [&](const std::string& tmp) { write_png_preview(tmp, image, scale); });
  outputs.commit();
  return 0;
}

static Command::Action declare_preview(CLI::App& app) {
  struct Args {
    std::string exr, png;
    double scale = 0;
  };
  auto a = std::make_shared<Args>();
  app.add_option("image", a->exr, "EXR image")->required();
  app.add_option("-o,--output", a->png, "PNG to write")->required();
  app.add_option("--scale", a->scale,
                 "multiply XYZ by this (Y = 1 is white) instead of exposing by the log-average "
                 "luminance")
      ->check(cli::positive_number());
  return [a] { return run_preview(a->exr, a->png, a->scale); };
}

KASHA_REGISTER_COMMAND(preview, "preview", "an EXR as a tone-mapped sRGB PNG", 7, false,
                       declare_preview);

}  // namespace kasha
