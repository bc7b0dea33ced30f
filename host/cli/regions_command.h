#pragma once
// `kasha regions`: an image's mean XYZ over each shape of its scene, from pixels well inside the
// shape — a rendered sample measured as a photographed one would be. With a white-reference image
// (the same scene and light with the samples replaced by a perfect white diffuser, as a white
// standard is measured in the sample's place), also XYZ relative to that white (Y = 100) and
// CIELAB about it.
#include <string>

namespace kasha {

struct RegionsArgs {
  std::string scene, image, white, json;
  double margin_px = 1;
};

int run_regions(const RegionsArgs& args);

}  // namespace kasha
