#include "colorimetry/colorimetry_report.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "core/printable.h"

namespace kasha {

namespace {

int observer_deg(Observer o) {
  return o == Observer::cie1964_10deg ? 10 : 2;
}

nlohmann::json per_bin(const WavelengthGrid& grid, const std::vector<double>& value) {
  std::vector<double> nm;
  for (int i = 0; i < grid.bins; ++i) nm.push_back(grid.center(i));
  return {{"nm", nm}, {"value", value}};  // NaN (undefined) is written as null
}

nlohmann::json illuminant_json(const Colorimetry& c, const IlluminantColorimetry& r) {
  nlohmann::json j;
  j["illuminant"] = json_text(r.illuminant);
  j["white_XYZ"] = r.white;
  j["XYZ"] = r.xyz;
  j["Lab"] = r.lab;
  j["whiteness"] = r.whiteness.w;
  j["tint"] = r.whiteness.t;
  j["whiteness_in_range"] = r.whiteness.in_range;
  j["beta"] = per_bin(c.grid, r.beta.total());
  j["beta_reflected"] = per_bin(c.grid, r.beta.reflected);
  j["beta_fluorescent"] = per_bin(c.grid, r.beta.fluorescent);
  if (r.as_is)
    j["as_is"] = {{"XYZ", r.as_is->xyz}, {"Lab", r.as_is->lab}, {"delta_E00", r.as_is->delta_e00}};
  return j;
}

// A label as a CSV cell: UTF-8 as in the JSON (json_text), quoted where it holds a separator.
std::string csv_field(const std::string& label) {
  const std::string s = json_text(label);
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string numbers(const std::vector<double>& v, const char* format) {
  std::string out;
  char buffer[64];
  for (double x : v) {
    std::snprintf(buffer, sizeof buffer, format, x);
    out += buffer;
  }
  return out;
}

}  // namespace

nlohmann::json colorimetry_json(const Colorimetry& c, const std::string& material_file) {
  nlohmann::json j;
  j["kasha_colorimetry"] = 1;
  j["material"] = c.material.name;
  j["material_file"] = json_text(material_file);
  j["observer"] = observer_name(c.observer);
  j["observer_deg"] = observer_deg(c.observer);
  j["geometry"] =
      "open: the hemisphere above the sample radiates the illuminant, nothing else; gloss left out";
  j["wavelengths"] = {{"min_nm", c.grid.min_nm},
                      {"max_nm", c.grid.max_nm()},
                      {"bin_nm", c.grid.bin_nm},
                      {"bins", c.grid.bins}};
  if (c.as_is)
    j["as_is_material"] = {{"lamp", json_text(c.as_is->lamp)},
                           {"clipped_nm", c.as_is->clipped_nm},
                           {"unlit_nm", c.as_is->unlit_nm},
                           {"reflectance", per_bin(c.grid, c.as_is->reflectance)}};
  if (c.illuminants.size() == 1) {
    j.update(illuminant_json(c, c.illuminants[0]));
  } else {
    j["illuminants"] = nlohmann::json::array();
    for (const IlluminantColorimetry& r : c.illuminants)
      j["illuminants"].push_back(illuminant_json(c, r));
  }
  return j;
}

std::string colorimetry_csv(const Colorimetry& c) {
  std::string out = "illuminant,observer_deg,X,Y,Z,L,a,b,whiteness,tint,whiteness_in_range";
  if (c.as_is) out += ",as_is_X,as_is_Y,as_is_Z,as_is_L,as_is_a,as_is_b,delta_E00";
  out += "\n";
  for (const IlluminantColorimetry& r : c.illuminants) {
    out += csv_field(r.illuminant) + "," + std::to_string(observer_deg(c.observer));
    out += numbers(
        {r.xyz[0], r.xyz[1], r.xyz[2], r.lab[0], r.lab[1], r.lab[2], r.whiteness.w, r.whiteness.t},
        ",%.6g");
    out += r.whiteness.in_range ? ",true" : ",false";
    if (r.as_is)
      out += numbers({r.as_is->xyz[0], r.as_is->xyz[1], r.as_is->xyz[2], r.as_is->lab[0],
                      r.as_is->lab[1], r.as_is->lab[2], r.as_is->delta_e00},
                     ",%.6g");
    out += "\n";
  }
  return out;
}

std::string colorimetry_table(const Colorimetry& c, const std::string& material_file) {
  std::ostringstream o;
  // Names and labels are input bytes: printable() keeps terminal controls off the terminal.
  o << "material: " << printable(c.material.name) << " (" << printable(material_file) << ")\n";
  o << "observer: " << observer_name(c.observer) << "; wavelengths: " << c.grid.describe()
    << "; open geometry, perfect white Y = 100\n";
  if (c.as_is) {
    o << "as is: the radiance factor under " << printable(c.as_is->lamp)
      << " as a passive reflectance";
    if (!c.as_is->clipped_nm.empty())
      o << ", clipped to 1 at" << numbers(c.as_is->clipped_nm, " %g") << " nm";
    o << "\n";
  }
  // The label column fits the longest illuminant as given (a name, a file, a JSON value).
  size_t width = 10;
  for (const IlluminantColorimetry& r : c.illuminants)
    width = std::max(width, printable(r.illuminant).size());
  char line[256];
  std::snprintf(line, sizeof line, " %8s %8s %8s %7s %7s %7s %7s %6s%s\n", "X", "Y", "Z", "L*",
                "a*", "b*", "W", "T", c.as_is ? "  ΔE00 as is" : "");
  o << std::left << std::setw(static_cast<int>(width)) << "illuminant" << line;
  bool any_out = false;
  for (const IlluminantColorimetry& r : c.illuminants) {
    any_out = any_out || !r.whiteness.in_range;
    std::snprintf(line, sizeof line, " %8.3f %8.3f %8.3f %7.2f %7.2f %7.2f %7.2f %6.2f%s", r.xyz[0],
                  r.xyz[1], r.xyz[2], r.lab[0], r.lab[1], r.lab[2], r.whiteness.w, r.whiteness.t,
                  r.whiteness.in_range ? "" : "*");
    o << std::setw(static_cast<int>(width)) << printable(r.illuminant) << line;
    if (r.as_is) {
      std::snprintf(line, sizeof line, " %12.2f", r.as_is->delta_e00);
      o << line;
    }
    o << "\n";
  }
  if (any_out)
    o << "* W, T outside CIE 15's limits of use (40 < W < 5Y − 280, −4 < T < 2): not a "
         "commercial white\n";
  return o.str();
}

}  // namespace kasha
