// `kasha colorimetry`: a material's total radiance factor, XYZ, CIELAB and CIE whiteness/tint under
// each illuminant, and ΔE2000 against its "as is" material.

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "colorimetry/colorimetry_report.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/output_set.h"
#include "core/python_script.h"
#include "spectrum/spectrum_argument.h"

namespace kasha {

struct ColorimetryArgs {
  std::string material, json, csv, plot, as_is, write_as_is;
  std::vector<std::string> illuminants;  // default: D65
  int observer = 2;                      // 2 or 10 (degrees)
  double bin_nm = 10;
};

// The figure is drawn from the JSON result, given to the plotter on its stdin: no scratch file.
static void write_plot(const std::string& path, const std::string& who,
                       const nlohmann::json& result) {
  run_embedded_python("plot_colorimetry.py", {"/dev/stdin", path}, who, result.dump());
}

static int run_colorimetry(const ColorimetryArgs& a) {
  OutputSet outputs;
  outputs.input(a.material, "the material file");
  for (const std::string& text : a.illuminants) outputs.input(text, "the --illuminant file");
  outputs.input(a.as_is, "the --as-is file");
  outputs.file("--json", a.json);
  outputs.file("--csv", a.csv);
  outputs.file("--plot", a.plot);
  outputs.file("--write-as-is", a.write_as_is);

  ColorimetryRequest request;
  request.material = load_material_file(a.material, "");
  if (request.material.kind != MaterialKind::measured)
    throw Error(a.material +
                ": a dielectric or conductor is an interface, not a surface colour: "
                "colorimetry takes a measured material");
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

  outputs.inputs_read("a file the spectra or the material read");
  Colorimetry c = evaluate_colorimetry(request);
  nlohmann::json result = colorimetry_json(c, a.material);
  if (!a.plot.empty())
    outputs.write(a.plot,
                  [&](const std::string& tmp) { write_plot(tmp, "--plot " + a.plot, result); });
  if (!a.json.empty())
    outputs.write(
        a.json, [&](const std::string& tmp) { write_text_atomically(tmp, result.dump(1) + "\n"); });
  if (!a.csv.empty())
    outputs.write(a.csv,
                  [&](const std::string& tmp) { write_text_atomically(tmp, colorimetry_csv(c)); });
  if (!a.write_as_is.empty())
    outputs.write(a.write_as_is,
                  [&](const std::string& tmp) { write_as_is_material(tmp, *c.as_is, a.material); });
  outputs.commit();
  std::fputs(colorimetry_table(c, a.material).c_str(), stdout);
  return 0;
}

static Command::Action declare_colorimetry(CLI::App& app) {
  auto col = std::make_shared<ColorimetryArgs>();
  app.add_option("material", col->material, "material JSON file")->required();
  app.add_option("--illuminant", col->illuminants,
                 "a spectrum: built-in name (D65, A, F11, …), CSV file or JSON value; repeat for a "
                 "table (default D65)");
  app.add_option("--observer", col->observer, "CIE 1931 2° or CIE 1964 10° (default 2)")
      ->check(cli::one_of({"2", "10"}));
  app.add_option("--bin-nm", col->bin_nm, "wavelength bin width (default 10)")
      ->check(cli::number_within(0.1, 100.0));
  CLI::Option* as_is = app.add_option(
      "--as-is", col->as_is,
      "compare with the material taken \"as is\": its radiance factor under this lamp "
      "as a plain reflectance (ΔE2000 per illuminant)");
  // A usage error: the "as is" material is taken under the --as-is lamp.
  app.add_option("--write-as-is", col->write_as_is,
                 "write that \"as is\" material as a material file (needs --as-is)")
      ->needs(as_is);
  app.add_option("--json", col->json, "results as JSON");
  app.add_option("--csv", col->csv, "results as CSV, a row per illuminant");
  app.add_option("--plot", col->plot, "radiance factors as a PNG figure");
  return [col] { return run_colorimetry(*col); };
}

KASHA_REGISTER_COMMAND(
    colorimetry, "colorimetry",
    "a material's total radiance factor, XYZ, CIELAB and CIE whiteness/tint under illuminants", 5,
    false, declare_colorimetry);

}  // namespace kasha
