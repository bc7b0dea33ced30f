#include "cli/colorimetry_command.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "colorimetry/colorimetry_report.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/python_script.h"
#include "spectrum/spectrum_argument.h"

namespace kasha {

namespace fs = std::filesystem;

// An output must go to an existing directory and may replace neither an input nor something that
// is not a regular file.
static void check_output(const std::string& path, const std::string& option,
                         const std::string& input) {
  if (path.empty()) return;
  fs::path p(path), dir = p.parent_path();
  if (!dir.empty() && !fs::is_directory(dir))
    throw Error(option + " " + path + ": directory " + dir.string() + " does not exist");
  if (!fs::exists(p)) return;
  if (!fs::is_regular_file(p)) throw Error(option + " " + path + ": not a regular file");
  std::error_code ec;
  if (fs::equivalent(p, input, ec))
    throw Error(option + " " + path + ": would overwrite the input");
}

// The figure is drawn from the JSON result in a scratch directory, then renamed into place.
static void write_plot(const std::string& path, const nlohmann::json& result) {
  fs::path scratch = fs::temp_directory_path() / ("kasha-colorimetry-" + std::to_string(getpid()));
  fs::create_directories(scratch);
  try {
    write_text_atomically((scratch / "result.json").string(), result.dump());
    write_atomically(path, [&](const std::string& tmp) {
      run_embedded_python("plot_colorimetry.py", scratch.string(),
                          {(scratch / "result.json").string(), tmp}, "--plot " + path);
    });
  } catch (...) {
    std::error_code ec;
    fs::remove_all(scratch, ec);
    throw;
  }
  fs::remove_all(scratch);
}

int run_colorimetry(const ColorimetryArgs& a) {
  for (const auto& [path, option] : {std::pair{a.json, "--json"},
                                     {a.csv, "--csv"},
                                     {a.plot, "--plot"},
                                     {a.write_as_is, "--write-as-is"}})
    check_output(path, option, a.material);
  if (!a.write_as_is.empty() && a.as_is.empty())
    throw Error("--write-as-is: give the lamp the \"as is\" material is taken under (--as-is)");

  ColorimetryRequest request;
  request.material = load_material_file(a.material, "");
  request.observer = a.observer == 10 ? Observer::cie1964_10deg : Observer::cie1931_2deg;
  request.bin_nm = a.bin_nm;
  const std::vector<std::string> names =
      a.illuminants.empty() ? std::vector<std::string>{"D65"} : a.illuminants;
  for (const std::string& text : names)
    request.illuminants.push_back(
        {text, parse_spectrum_argument(text, "--illuminant"), "--illuminant " + text});
  if (!a.as_is.empty())
    request.as_is_lamp = {a.as_is, parse_spectrum_argument(a.as_is, "--as-is"),
                          "--as-is " + a.as_is};

  Colorimetry c = evaluate_colorimetry(request);
  nlohmann::json result = colorimetry_json(c, a.material);
  // The figure first: it is the step most likely to fail, and nothing is written before it.
  if (!a.plot.empty()) write_plot(a.plot, result);
  if (!a.json.empty()) write_text_atomically(a.json, result.dump(1) + "\n");
  if (!a.csv.empty()) write_text_atomically(a.csv, colorimetry_csv(c));
  if (!a.write_as_is.empty()) write_as_is_material(a.write_as_is, *c.as_is, a.material);
  std::fputs(colorimetry_table(c, a.material).c_str(), stdout);
  return 0;
}

}  // namespace kasha
