#include "cli/preview_command.h"

#include "image/exr_io.h"
#include "image/png_preview.h"

namespace kasha {

int run_preview(const std::string& exr, const std::string& png, double scale) {
  write_png_preview(png, read_exr(exr), scale);
  return 0;
}

}  // namespace kasha
