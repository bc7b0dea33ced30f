#include "cli/render_options.h"

#include "cli/command_line_errors.h"
#include "core/printable.h"

namespace kasha::cli {

namespace {

CLI::Validator check_for(const IntegratorOption& s) {
  using V = IntegratorOption::Value;
  switch (s.value) {
    case V::integer:
    case V::bytes:
      return integer_within(static_cast<long long>(s.lo), static_cast<long long>(s.hi));
    case V::number:
      return number_within(s.lo, s.hi);
    case V::positive:
      return positive_number(s.hi);
    case V::choice:
    case V::flag:
    case V::depth_cap:
      break;
  }
  return CLI::Validator();
}

// An enumerated setting: its name checked, then stored once as the enum's value.
CLI::Option* add_choice(CLI::App& app, const IntegratorOption& s, const ChoiceField& field) {
  const std::vector<std::string>& names = *field.names;
  return app
      .add_option_function<std::string>(
          s.name,
          [field, names](const std::string& v) {
            field.set(
                static_cast<size_t>(std::find(names.begin(), names.end(), v) - names.begin()));
          },
          s.help)
      ->check(one_of(names));
}

// A depth cap: an integer within the declaration's range, or `scene` (kSceneDepthCap, which the
// render resolves once it has read the scene: render/depth_cap.h).
CLI::Option* add_depth_cap(CLI::App& app, const IntegratorOption& s, int* field) {
  CLI::Validator integer =
      integer_within(static_cast<long long>(s.lo), static_cast<long long>(s.hi));
  return app
      .add_option_function<std::string>(
          s.name,
          [field](const std::string& v) {
            *field = v == "scene" ? IntegratorSettings::kSceneDepthCap : std::stoi(v);
          },
          s.help)
      ->check(CLI::Validator(
          [integer](std::string& v) mutable -> std::string {
            if (v == "scene") return "";
            const std::string problem = integer(v);
            return problem.empty() ? problem : problem + " (or scene)";
          },
          "N|scene", "N|scene"));
}

}  // namespace

void add_setting_options(CLI::App& app, IntegratorSettings& settings,
                         const std::vector<std::string>& names) {
  for (const RenderOption& o : render_options()) {
    const IntegratorOption& s = o.option;
    if (!names.empty() && std::find(names.begin(), names.end(), s.name) == names.end()) continue;
    std::visit(
        [&](const auto& field) {
          using T = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<T, ChoiceField>) {
            add_choice(app, s, field);
          } else if constexpr (std::is_same_v<T, bool*>) {
            app.add_flag(s.name, *field, s.help);
          } else if (s.value == IntegratorOption::Value::depth_cap) {
            if constexpr (std::is_same_v<T, int*>) add_depth_cap(app, s, field);
          } else {
            CLI::Option* option = app.add_option(s.name, *field, s.help);
            if (s.value == IntegratorOption::Value::bytes) option->transform(byte_size());
            option->check(check_for(s));
          }
        },
        s.field(settings));
  }
}

std::vector<std::string> integrator_options_given(const CLI::App& app) {
  std::vector<std::string> given;
  for (const RenderOption& o : render_options())
    if (!o.common() && app.count(o.option.name) > 0) given.push_back(o.option.name);
  return given;
}

CLI::Option* add_material_option(CLI::App& app, std::vector<MaterialOverride>& materials) {
  return app
      .add_option_function<std::vector<std::string>>(
          "--material",
          [&materials](const std::vector<std::string>& values) {
            materials.clear();
            for (const std::string& v : values) {
              const size_t eq = v.find('=');
              materials.push_back({v.substr(0, eq), v.substr(eq + 1)});
            }
          },
          "NAME=FILE: render the scene's material NAME (or a pbrt-v4 object NAME) with the "
          "material file FILE (repeatable)")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            const size_t eq = v.find('=');
            if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
              return "expected NAME=FILE, got \"" + printable(v) + "\"";
            return "";
          },
          "NAME=FILE"))
      ->allow_extra_args(false);
}

CLI::Option* add_bin_option(CLI::App& app, double& bin_nm) {
  // The grid's own limits (docs/formats.md#wavelengths).
  return app
      .add_option("--bin-nm", bin_nm,
                  "the wavelength bins' width in nm, in place of the scene's \"wavelengths\" "
                  "(the range automatic): narrower bins follow steep spectra closer, at a cost")
      ->check(number_within(0.1, 1000));
}

CLI::Option* add_device_option(CLI::App& app, std::string& device) {
  return app
      .add_option("--device", device,
                  "OpenCL devices: an index, a comma-separated list (0,1; an index named twice "
                  "gives its device a second queue) or all; see `kasha devices`")
      ->check(device_list());
}

}  // namespace kasha::cli
