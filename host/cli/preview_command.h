#pragma once
// `kasha preview`: an EXR as a PNG preview, exposed by Reinhard's key or by a given scale (so that
// several images can share one exposure).
#include <string>

namespace kasha {

int run_preview(const std::string& exr, const std::string& png, double scale);

}  // namespace kasha
