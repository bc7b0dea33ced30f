// `kasha delta-e`: the CIEDE2000 difference between two CIELAB colours.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "colorimetry/ciede2000.h"
#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

// Ten times beyond any surface colour, so none is refused, and far below where CIEDE2000's C'⁷
// overflows (1e308 gave -nan): the result is finite for every accepted pair (docs/commands.md).
constexpr double kMaxLightness = 1e4, kMaxChroma = 1e4;

// The text split at every comma, empty fields kept ("50,0," is three fields, the last empty).
std::vector<std::string> fields(const std::string& text) {
  std::vector<std::string> out(1);
  for (char ch : text) {
    if (ch == ',')
      out.emplace_back();
    else
      out.back() += ch;
  }
  return out;
}

std::string trimmed(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// "" if `text` is "L,a,b" (three finite numbers within the range above, stored in lab), else what
// is wrong with it: a command-line error, so the validator below reports it with exit code 2. Each
// field is checked by the command line's own number check. (An empty value is named by the
// command line's safety net, cli::require_values.)
std::string lab_problem(const std::string& text, Vec3d& lab) {
  const std::vector<std::string> parts = fields(text);
  const std::string quoted = "\"" + printable(text) + "\"";
  if (parts.size() != 3) return quoted + " is not L*,a*,b* (three numbers separated by commas)";
  const char* names[3] = {"L*", "a*", "b*"};
  for (int k = 0; k < 3; ++k) {
    std::string field = trimmed(parts[k]);
    if (field.empty()) return std::string(names[k]) + " is empty in " + quoted;
    const std::string problem = k == 0 ? cli::number_within(0, kMaxLightness)(field)
                                       : cli::number_within(-kMaxChroma, kMaxChroma)(field);
    if (!problem.empty()) return std::string(names[k]) + " " + problem;
    lab[k] = std::strtod(field.c_str(), nullptr);
  }
  return "";
}

CLI::Validator lab_colour() {
  return CLI::Validator(
      [](std::string& text) {
        Vec3d lab;
        return lab_problem(text, lab);
      },
      "L*,a*,b*", "LAB");
}

Vec3d parse_lab(const std::string& text) {
  Vec3d lab{0, 0, 0};
  const std::string problem = lab_problem(text, lab);
  if (!problem.empty()) throw Error(printable(text) + ": " + problem);  // the validator ran first
  return lab;
}

}  // namespace

static int run_delta_e(const std::string& lab1, const std::string& lab2) {
  const double d = ciede2000(parse_lab(lab1), parse_lab(lab2));
  if (!std::isfinite(d)) throw Error("delta-e: the difference is not finite");  // never, in range
  std::printf("%.4f\n", d);
  return 0;
}

static Command::Action declare_delta_e(CLI::App& app) {
  auto labs = std::make_shared<std::pair<std::string, std::string>>();
  app.add_option("lab1", labs->first, "L*,a*,b*: L* in [0, 10000], a*, b* in [-10000, 10000]")
      ->required()
      ->check(lab_colour());
  app.add_option("lab2", labs->second, "L*,a*,b*")->required()->check(lab_colour());
  return [labs] { return run_delta_e(labs->first, labs->second); };
}

KASHA_REGISTER_COMMAND(delta_e, "delta-e",
                       "the CIEDE2000 colour difference between two CIELAB colours", 6, false,
                       declare_delta_e);

}  // namespace kasha
