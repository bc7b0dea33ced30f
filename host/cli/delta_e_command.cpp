// `kasha delta-e`: the CIEDE2000 difference between two CIELAB colours.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "colorimetry/ciede2000.h"
#include "core/error.h"

namespace kasha {

// "L,a,b": three finite numbers separated by commas.
static Vec3d parse_lab(const std::string& text) {
  Vec3d lab{0, 0, 0};
  const char* p = text.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    lab[k] = std::strtod(p, &end);
    if (end == p || !std::isfinite(lab[k]) || *end != (k < 2 ? ',' : '\0'))
      throw Error("delta-e " + text + ": expected L*,a*,b* (three numbers separated by commas)");
    p = end + (k < 2 ? 1 : 0);
  }
  return lab;
}

static int run_delta_e(const std::string& lab1, const std::string& lab2) {
  std::printf("%.4f\n", ciede2000(parse_lab(lab1), parse_lab(lab2)));
  return 0;
}

static Command::Action declare_delta_e(CLI::App& app) {
  auto labs = std::make_shared<std::pair<std::string, std::string>>();
  app.add_option("lab1", labs->first, "L*,a*,b*")->required();
  app.add_option("lab2", labs->second, "L*,a*,b*")->required();
  return [labs] { return run_delta_e(labs->first, labs->second); };
}

KASHA_REGISTER_COMMAND(delta_e, "delta-e",
                       "the CIEDE2000 colour difference between two CIELAB colours", 6, false,
                       declare_delta_e);

}  // namespace kasha
