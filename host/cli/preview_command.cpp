#include "cli/preview_command.h"

#include "core/output_set.h"
#include "image/exr_io.h"
#include "image/png_preview.h"

namespace kasha {

int run_preview(const std::string& exr, const std::string& png, double scale) {
  OutputSet outputs;
  outputs.input(exr, "the image");
  outputs.file("-o", png);
  Image image = read_exr(exr);
  outputs.write(png, [&](const std::string& tmp) { write_png_preview(tmp, image, scale); });
  outputs.commit();
  return 0;
}

}  // namespace kasha
