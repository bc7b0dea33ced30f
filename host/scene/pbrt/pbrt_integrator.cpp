#include "scene/pbrt/pbrt_integrator.h"

#include <set>

namespace kasha {

std::optional<int> pbrt_integrator_max_depth(const std::string& type, const PbrtParameters& params,
                                             const PbrtLocation& where) {
  // pbrt-v4's integrators.cpp: each of these reads "maxdepth" with a default of 5.
  static const std::set<std::string> with_depth = {"path",          "simplepath", "lightpath",
                                                   "simplevolpath", "volpath",    "bdpt",
                                                   "mlt",           "sppm",       "randomwalk"};
  std::optional<int> depth;
  std::string used = "it names no maxdepth, so --max-depth scene is refused";
  if (with_depth.count(type)) {
    const int given = params.get_int("maxdepth", kPbrtDefaultMaxDepth);
    if (given >= 0) {
      depth = given;
      used = "its maxdepth " + std::to_string(given) + " is what --max-depth scene uses";
    } else {
      used = "its maxdepth " + std::to_string(given) +
             " caps nothing, so --max-depth scene is refused";
    }
  }
  pbrt_warn(where, "Integrator " + in_quotes(type) +
                       " is ignored: kasha's --integrator, --spp and --passes decide, unbiased "
                       "unless --max-depth caps the path length; " +
                       used + " (docs/pbrt-import.md)");
  return depth;
}

}  // namespace kasha
