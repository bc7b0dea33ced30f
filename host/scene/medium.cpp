#include "scene/medium.h"

#include <cmath>

#include "spectrum/spectrum_parser.h"

namespace kasha {

bool Medium::scatters() const {
  for (double s : sigma_s)
    if (s > 0) return true;
  return false;
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
  return m;
}

}  // namespace kasha
