#include "scene/pbrt/pbrt_spectra.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "color/cie_observer.h"
#include "core/error.h"
#include "core/json_node.h"
#include "core/printable.h"
#include "scene/pbrt/pbrt_color_space.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

namespace {

// pbrt-v4's named spectra that kasha has under another name: CIE illuminants and glasses. Its
// metals are taken by the conductor (pbrt_materials.cpp), which knows both η and k.
const std::map<std::string, std::string>& named_spectra() {
  static const std::map<std::string, std::string> names = [] {
    std::map<std::string, std::string> n = {
        {"stdillum-A", "A"},           {"stdillum-D50", "D50"},  {"stdillum-D65", "D65"},
        {"illum-acesD60", "ACES_D60"}, {"glass-BK7", "BK7"},     {"glass-F11", "SF11"},
        {"glass-BAF10", "BAF10"},      {"glass-FK51A", "FK51A"}, {"glass-LASF9", "LASF9"},
        {"glass-F5", "SF5"},           {"glass-F10", "SF10"},
    };
    for (int f = 1; f <= 12; ++f) n["stdillum-F" + std::to_string(f)] = "F" + std::to_string(f);
    return n;
  }();
  return names;
}

// p's RGB as linear sRGB (kasha's uplift is sRGB's); a colour outside what sRGB holds is brought
// into it (components clamped to [0, 1] for a reflectance, to ≥ 0 otherwise), with a warning.
std::array<double, 3> in_srgb(const PbrtParameter& p, PbrtSpectrumUse use) {
  std::array<double, 3> rgb = {p.numbers[0], p.numbers[1], p.numbers[2]};
  if (p.color_space == "srgb") return rgb;
  const PbrtColorSpace* space = pbrt_color_space(p.color_space);
  if (!space) pbrt_fail(p.where, "unknown color space " + in_quotes(p.color_space));
  rgb = pbrt_rgb_to_srgb(*space, rgb, use != PbrtSpectrumUse::kIlluminant);
  const double hi = use == PbrtSpectrumUse::kAlbedo ? 1 : INFINITY;
  bool clamped = false;
  for (double& v : rgb) {
    const double c = std::clamp(v, 0.0, hi);
    clamped = clamped || std::abs(c - v) > 1e-9;
    v = c;
  }
  if (clamped)
    pbrt_warn(p.where, in_quotes(p.declaration()) + " in ColorSpace " + in_quotes(space->name) +
                           " lies outside sRGB, which kasha's RGB uplift covers: clamped into it");
  return rgb;
}

}  // namespace

nlohmann::json pbrt_spectrum(const PbrtParameter& p, PbrtSpectrumUse use,
                             const std::filesystem::path& base_dir) {
  const std::string what = "\"" + printable(p.declaration()) + "\"";
  if (p.type == "float") {
    if (p.numbers.size() != 1) pbrt_fail(p.where, what + " takes one value");
    if (p.numbers[0] < 0) pbrt_fail(p.where, what + " is negative");
    return p.numbers[0];
  }
  if (p.type == "rgb") {
    if (p.numbers.size() != 3) pbrt_fail(p.where, what + " takes one RGB triple");
    for (double v : p.numbers)
      if (v < 0) pbrt_fail(p.where, what + " has a negative component");
    if (use == PbrtSpectrumUse::kAlbedo)
      for (double v : p.numbers)
        if (v > 1) pbrt_fail(p.where, what + " has a component above 1 (a reflectance)");
    const std::array<double, 3> rgb = in_srgb(p, use);
    const std::vector<double> triple(rgb.begin(), rgb.end());
    if (use == PbrtSpectrumUse::kIlluminant) return {{"rgb_illuminant", triple}};
    if (use == PbrtSpectrumUse::kUnbounded) return pbrt_rgb_unbounded(rgb);
    return {{"rgb", triple}};
  }
  if (p.type == "blackbody") {
    if (p.numbers.size() != 1 || !(p.numbers[0] > 0))
      pbrt_fail(p.where, what + " takes one positive temperature in K");
    if (use == PbrtSpectrumUse::kIlluminant) return {{"blackbody_K", p.numbers[0]}};
    // pbrt-v4's BlackbodySpectrum outside a light: Planck's law over its peak.
    const double peak = BlackbodySpectrum(p.numbers[0]).peak();
    return {{"blackbody_K", p.numbers[0]}, {"scale", 1 / peak}};
  }
  if (p.type != "spectrum") pbrt_fail(p.where, what + " is not a spectrum");
  if (!p.numbers.empty()) {
    std::vector<double> nm, value;
    for (size_t i = 0; i + 1 < p.numbers.size(); i += 2) {
      nm.push_back(p.numbers[i]);
      value.push_back(p.numbers[i + 1]);
    }
    if (nm.size() < 2) pbrt_fail(p.where, what + " needs at least two wavelength-value pairs");
    for (size_t i = 1; i < nm.size(); ++i)
      if (!(nm[i] > nm[i - 1])) pbrt_fail(p.where, what + ": wavelengths must increase");
    for (double v : value)
      if (v < 0) pbrt_fail(p.where, what + " has a negative value");
    return {{"nm", nm}, {"value", value}};
  }
  if (p.strings.size() != 1) pbrt_fail(p.where, what + " takes one name or file");
  const std::string& name = p.strings[0];
  auto known = named_spectra().find(name);
  if (known != named_spectra().end()) return known->second;
  if (name.rfind("metal-", 0) == 0 || name.rfind("glass-", 0) == 0 ||
      name.rfind("stdillum-", 0) == 0 || name.rfind("illum-", 0) == 0 ||
      name.rfind("canon_", 0) == 0 || name.rfind("nikon_", 0) == 0 || name.rfind("sony_", 0) == 0)
    pbrt_fail(p.where, what + ": the named spectrum \"" + printable(name) +
                           "\" is not among kasha's (pbrt-v4's stdillum-A, -D50, -D65, "
                           "-F1…F12, illum-acesD60, glass-BK7, -BAF10, -FK51A, -LASF9, -F5, "
                           "-F10, -F11, and metal-Ag/Al/Au/Cu/CuZn/MgO/TiO2 for a conductor; no "
                           "camera sensor curves)");
  // A file of wavelength-value pairs, relative to the scene's folder (as the scene's JSON
  // resolves it).
  (void)base_dir;
  return {{"csv", name}};
}

nlohmann::json pbrt_tabulated(const std::function<double(double)>& f) {
  // pbrt-v4 samples 360–830 nm; kasha's grid may reach further (a UV lamp's 300 nm): beyond the
  // table its end values hold, as a kasha table would otherwise fall to zero there (an η of 0).
  std::vector<double> nm{1}, value{f(kPbrtTableMinNm)};
  for (int l = kPbrtTableMinNm; l <= kPbrtTableMaxNm; ++l) {
    nm.push_back(l);
    value.push_back(f(l));
  }
  nm.push_back(1e5);
  value.push_back(value.back());
  return {{"nm", nm}, {"value", value}};
}

nlohmann::json pbrt_rgb_unbounded(const std::array<double, 3>& rgb) {
  double scale = 0;
  const SigmoidCoefficients c = rgb_unbounded_sigmoid(rgb, &scale);
  if (!(scale > 0)) return 0.0;
  return pbrt_tabulated([&](double nm) { return scale * sigmoid_spectrum(c, nm); });
}

namespace {
// ∫ ȳ s in pbrt-v4's 1 nm steps over 360–830 nm.
double photometric_sum(const Spectrum& s) {
  const SpectrumPtr& ybar = cie_cmf(Observer::cie1931_2deg)[1];
  double sum = 0;
  for (int nm = 360; nm <= 830; ++nm) sum += ybar->value(nm) * s.value(nm);
  return sum;
}
}  // namespace

SpectrumPtr pbrt_parse_spectrum(const nlohmann::json& spectrum,
                                const std::filesystem::path& base_dir, const PbrtLocation& where) {
  static const std::string kWhat = "a pbrt-v4 spectrum";
  try {
    return parse_spectrum(JsonNode::parse_text(
        spectrum.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), kWhat, base_dir));
  } catch (const Error& e) {
    // "a pbrt-v4 spectrum: /PATH: why" names no file: the statement's line does.
    std::string why = e.what();
    if (why.rfind(kWhat + ": /", 0) == 0) why = why.substr(why.find(": ", kWhat.size() + 2) + 2);
    pbrt_fail(where, why);
  }
}

double pbrt_photometric(const nlohmann::json& spectrum, const std::filesystem::path& base_dir,
                        const PbrtLocation& where) {
  // pbrt-v4 normalises an RGB illuminant by its illuminant alone; the RGB's own luminance stays.
  if (spectrum.is_object() && spectrum.contains("rgb_illuminant")) return pbrt_d65_photometric();
  return photometric_sum(*pbrt_parse_spectrum(spectrum, base_dir, where));
}

double pbrt_d65_photometric() {
  static const double d65 = photometric_sum(
      *parse_spectrum(JsonNode::parse_text(R"({"rgb_illuminant": [1, 1, 1]})", "D65", "")));
  return d65;
}

nlohmann::json pbrt_light_spectrum(const PbrtParameter* p, double scale,
                                   const std::filesystem::path& base_dir) {
  nlohmann::json s = p ? pbrt_spectrum(*p, PbrtSpectrumUse::kIlluminant, base_dir)
                       : nlohmann::json{{"rgb_illuminant", {1, 1, 1}}};
  const double y = pbrt_photometric(s, base_dir, p ? p->where : PbrtLocation{});
  if (!(y > 0)) {
    if (p) pbrt_fail(p->where, "\"" + printable(p->declaration()) + "\" emits no visible light");
    return 0;
  }
  if (s.is_string()) {
    // A built-in illuminant by name takes no scale: tabulated every nanometre of its support.
    const SpectrumPtr named = builtin_spectrum(s.get<std::string>());
    const SpectralSupport support = named->support();
    std::vector<double> nm, value;
    for (double l = std::ceil(support.lo_nm); l <= support.hi_nm; l += 1) {
      nm.push_back(l);
      value.push_back(named->value(l));
    }
    s = {{"nm", nm}, {"value", value}};
  }
  s["scale"] = scale / y;
  return s;
}

}  // namespace kasha
