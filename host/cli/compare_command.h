#pragma once
// `kasha compare IMAGE.exr REFERENCE.exr [--scene SCENE.json]`: the error of an image against a
// reference as the convergence log measures it, and, given the scene, with the pixels that see an
// emitter directly left out.
#include <string>

namespace kasha {

int run_compare(const std::string& image, const std::string& reference, const std::string& scene);

}  // namespace kasha
