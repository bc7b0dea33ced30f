// `kasha regions`: an image's mean XYZ over each shape of its scene, from pixels well inside the
// shape — a rendered sample measured as a photographed one would be. With a white-reference image
// (the same scene and light with the samples replaced by a perfect white diffuser, as a white
// standard is measured in the sample's place), also XYZ relative to that white (Y = 100) and
// CIELAB about it.
#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "colorimetry/cie_lab.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/output_set.h"
#include "core/printable.h"
#include "image/exr_io.h"
#include "study/image_regions.h"

namespace kasha {

struct RegionsArgs {
  std::string scene, image, white, json;
  double margin_px = 1;
};

static Image read_image_of(const Scene& scene, const std::string& path) {
  Image image = read_exr(path);
  if (image.width != scene.camera.width || image.height != scene.camera.height)
    throw Error(path + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " pixels, but the camera of " + scene.file + " is " +
                std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height));
  return image;
}

// printf into a string of any length (material names have none).
static std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
static std::string format(const char* fmt, ...) {
  va_list args, again;
  va_start(args, fmt);
  va_copy(again, args);
  std::string out(static_cast<size_t>(std::max(0, std::vsnprintf(nullptr, 0, fmt, args))), '\0');
  va_end(args);
  std::vsnprintf(out.data(), out.size() + 1, fmt, again);
  va_end(again);
  return out;
}

static Vec3d scaled(const Vec3d& v, double k) {
  return {k * v[0], k * v[1], k * v[2]};
}

// The white is dark in a region when one of its X, Y, Z is not positive there (a lamp's own face, a
// corner no light reaches): nothing relative to it, nor CIELAB (which divides by X, Y and Z).
static bool dark(const Vec3d& white) {
  return !(white[0] > 0 && white[1] > 0 && white[2] > 0);
}

// Every row is made before the first is printed, so an error (the white dark everywhere, no region
// at all) is the only output.
static int run_regions(const RegionsArgs& a) {
  OutputSet outputs;
  outputs.input(a.scene, "the scene file");
  outputs.input(a.image, "the image");
  outputs.input(a.white, "the --white image");
  outputs.file("--json", a.json);
  Scene scene = load_scene(a.scene);
  outputs.inputs_read("the scene's material or data file");
  Image image = read_image_of(scene, a.image);
  std::optional<Image> white;
  if (!a.white.empty()) white = read_image_of(scene, a.white);
  const std::vector<ShapeRegion> found = shape_regions(scene, scene.camera, a.margin_px);
  if (found.empty()) {
    char margin[32];
    std::snprintf(margin, sizeof margin, "%g", a.margin_px);
    throw Error(printable(a.scene) + ": no pixel sees one shape with --margin " + margin +
                " pixels around it, so there is no region to measure");
  }
  nlohmann::json regions = nlohmann::json::array();
  // The table is printed once the JSON is written: nothing on stdout before an error is known.
  std::vector<int> skipped;
  std::string rows;
  for (const ShapeRegion& r : found) {
    const ShapeInfo& shape = scene.shapes[r.shape];
    const std::string& material = scene.material_descs[shape.material].name;
    RegionXyz xyz = region_xyz(image, r.pixels);
    nlohmann::json region = {{"shape", r.shape},
                             {"type", shape.type},
                             {"material", material},
                             {"emitter", shape.emitter >= 0},
                             {"pixels", r.pixels.size()},
                             {"XYZ", xyz.mean},
                             {"standard_error", xyz.standard_error}};
    std::string lab;
    if (white) {
      // The white's own noise is left out of the relative standard error: give it more samples.
      RegionXyz w = region_xyz(*white, r.pixels);
      if (dark(w.mean)) {
        skipped.push_back(r.shape);
        continue;
      }
      const double k = 100 / w.mean[1];
      Vec3d relative = scaled(xyz.mean, k), l = xyz_to_lab(relative, scaled(w.mean, k));
      region["white_XYZ"] = w.mean;
      region["XYZ_relative"] = relative;
      region["standard_error_relative"] = scaled(xyz.standard_error, k);
      region["Lab"] = l;
      xyz.mean = relative;
      xyz.standard_error = scaled(xyz.standard_error, k);
      char text[96];
      std::snprintf(text, sizeof text, "; %.2f, %.2f, %.2f", l[0], l[1], l[2]);
      lab = text;
    }
    regions.push_back(region);
    // A material name is a JSON key: valid UTF-8, but it may hold terminal controls.
    rows += format("%5d  %-6s  %-24s %7zu  %.6g ± %.2g, %.6g ± %.2g, %.6g ± %.2g%s\n", r.shape,
                   printable(shape.type).c_str(), printable(material).c_str(), r.pixels.size(),
                   xyz.mean[0], xyz.standard_error[0], xyz.mean[1], xyz.standard_error[1],
                   xyz.mean[2], xyz.standard_error[2], lab.c_str());
  }
  if (regions.empty())
    throw Error("--white " + printable(a.white) +
                ": the white is dark (X, Y or Z not above 0) in every region, so nothing can be "
                "measured relative to it");
  std::string left_out;
  for (int shape : skipped) left_out += (left_out.empty() ? "" : ", ") + std::to_string(shape);
  if (!left_out.empty())
    left_out = "left out: shape" + std::string(skipped.size() > 1 ? "s " : " ") + left_out +
               " (the white is dark there: X, Y or Z not above 0)\n";
  if (!a.json.empty()) {
    // File names are command-line bytes: json_text() keeps the JSON UTF-8.
    const std::string text =
        nlohmann::json{{"scene", json_text(a.scene)}, {"image", json_text(a.image)},
                       {"white", json_text(a.white)}, {"margin_px", a.margin_px},
                       {"regions", regions},          {"skipped_shapes", skipped}}
            .dump(1) +
        "\n";
    outputs.write(a.json, [&](const std::string& tmp) { write_text_atomically(tmp, text); });
    outputs.commit();
  }
  std::printf("%5s  %-6s  %-24s %7s  %s\n%s%s", "shape", "type", "material", "pixels",
              white ? "X, Y, Z relative to the white (Y = 100) ± standard error; L*, a*, b*"
                    : "mean X, Y, Z ± standard error",
              rows.c_str(), left_out.c_str());
  return 0;
}

static Command::Action declare_regions(CLI::App& app) {
  auto reg = std::make_shared<RegionsArgs>();
  app.add_option("scene", reg->scene, "scene JSON file (its camera made the image)")->required();
  app.add_option("image", reg->image, "EXR image")->required();
  app.add_option("--margin", reg->margin_px,
                 "pixels count when the shape is also seen this many pixels around their centre "
                 "(default 1)")
      ->check(cli::number_within(0, 1 << 20));
  app.add_option("--white", reg->white,
                 "white-reference EXR (the samples replaced by a perfect white): adds XYZ "
                 "relative to it (Y = 100) and CIELAB");
  app.add_option("--json", reg->json, "the regions as JSON");
  return [reg] { return run_regions(*reg); };
}

KASHA_REGISTER_COMMAND(
    regions, "regions",
    "an image's mean XYZ over each shape of its scene, from pixels well inside it", 8, false,
    declare_regions);

}  // namespace kasha
