#include "scene/medium.h"

#include <cmath>

#include "core/error.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

bool Medium::scatters() const {
  for (double s : sigma_s)
    if (s > 0) return true;
  return !fluorophores.empty();
}

// One entry of a medium's "fluorophores": "absorption" (per scene unit of length), or
// "molar_absorption" (decadic, L·mol⁻¹·cm⁻¹) with "concentration" (mol·L⁻¹) and "unit_cm" (the
// scene's unit of length in cm, 100: metres); "quantum_yield" in [0, 1]; "emission".
static FluorophoreDesc parse_fluorophore(const JsonNode& node) {
  if (!node.is_object()) node.fail("expected a fluorophore object");
  FluorophoreDesc f;
  f.where = node.where();
  auto absorption = node.find("absorption"), molar = node.find("molar_absorption");
  if (absorption && molar) molar->fail("give \"absorption\" or \"molar_absorption\", not both");
  if (absorption) {
    f.absorption = parse_spectrum(*absorption);
  } else if (molar) {
    const double c = node.at("concentration").number_in(0, 1e3);
    double unit_cm = 100;
    if (auto u = node.find("unit_cm")) unit_cm = u->number_in(1e-12, 1e12);
    // Decadic absorbance per cm, ε c, as natural attenuation per scene unit: ln 10 · ε c · unit.
    f.absorption = parse_spectrum(*molar);
    f.absorption_scale = std::log(10.0) * c * unit_cm;
  } else {
    node.fail("a fluorophore needs its \"absorption\" (or \"molar_absorption\" and \"concentration\")");
  }
  f.quantum_yield = node.has("quantum_yield") ? node.at("quantum_yield").number_in(0, 1) : 1.0;
  f.emission = parse_spectrum(node.at("emission"));
  node.finish();
  return f;
}

MediumDesc parse_medium(const JsonNode& node, const std::string& name) {
  if (!node.is_object()) node.fail("expected a medium object");
  MediumDesc d;
  d.name = name;
  d.where = node.where();
  const std::string type = node.has("type") ? node.at("type").string() : "homogeneous";
  if (type != "homogeneous")
    node.at("type").fail("unknown medium type \"" + type + "\" (homogeneous)");
  // pbrt-v4's defaults: σa = σs = 1, scale 1, g 0.
  const auto coefficient = [&](const char* key) -> SpectrumPtr {
    if (auto c = node.find(key)) return parse_spectrum(*c);
    return std::make_shared<ConstantSpectrum>(1.0);
  };
  d.sigma_a = coefficient("sigma_a");
  d.sigma_s = coefficient("sigma_s");
  if (auto s = node.find("scale")) d.scale = s->number_in(0, 1e30);
  if (auto fl = node.find("fluorophores")) {
    if (!fl->is_array()) fl->fail("expected an array of fluorophores");
    if (fl->size() > static_cast<size_t>(kMaxMediumFluorophores))
      fl->fail("a medium holds at most " + std::to_string(kMaxMediumFluorophores) + " fluorophores");
    for (size_t k = 0; k < fl->size(); ++k) d.fluorophores.push_back(parse_fluorophore((*fl)[k]));
  }
  if (auto g = node.find("g")) {
    d.g = g->number();
    if (!(std::abs(d.g) < 1)) g->fail("the phase function's g must lie strictly between -1 and 1");
  }
  node.finish();
  return d;
}

int medium_index(const JsonNode& node, const std::vector<MediumDesc>& media) {
  if (node.is_null()) return -1;
  const std::string name = node.string();
  if (name.empty()) return -1;
  for (size_t i = 0; i < media.size(); ++i)
    if (media[i].name == name) return static_cast<int>(i);
  node.fail("no medium named \"" + name + "\" in the scene's \"media\"");
}

MediumInterface parse_medium_interface(const JsonNode& node, const std::vector<MediumDesc>& media) {
  if (!node.is_object()) node.fail("expected {\"inside\": MEDIUM, \"outside\": MEDIUM}");
  MediumInterface mi;
  if (auto in = node.find("inside")) mi.inside = medium_index(*in, media);
  if (auto out = node.find("outside")) mi.outside = medium_index(*out, media);
  node.finish();
  return mi;
}

Medium discretize_medium(const MediumDesc& desc, const WavelengthGrid& grid) {
  Medium m;
  m.sigma_a = grid.resample(*desc.sigma_a);
  m.sigma_s = grid.resample(*desc.sigma_s);
  for (double& v : m.sigma_a) v *= desc.scale;
  for (double& v : m.sigma_s) v *= desc.scale;
  m.g = desc.g;
  for (const FluorophoreDesc& fd : desc.fluorophores) {
    Fluorophore f;
    f.absorption = grid.resample(*fd.absorption);
    for (double& v : f.absorption) v *= fd.absorption_scale;
    f.quantum_yield = fd.quantum_yield;
    const std::vector<double> e = grid.resample(*fd.emission);
    double total = 0;
    for (double v : e) total += v;
    if (!(total > 0))
      throw Error(fd.where + "/emission: no emission on the wavelength grid " + grid.describe());
    for (double v : e) f.e_hat.push_back(v / total);
    m.fluorophores.push_back(f);
  }
  return m;
}

}  // namespace kasha
