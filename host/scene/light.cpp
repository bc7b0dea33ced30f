#include "scene/light.h"

#include <cmath>

#include "scene/limits.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

const char* light_type_name(LightType type) {
  switch (type) {
    case LightType::point: return "point";
    case LightType::spot: return "spot";
    case LightType::distant: return "distant";
    case LightType::infinite: return "infinite";
  }
  return "?";
}

double Light::cos_total() const { return std::cos(cone_deg * M_PI / 180.0); }
double Light::cos_falloff() const { return std::cos((cone_deg - cone_delta_deg) * M_PI / 180.0); }

double Light::integrated(double bin_nm) const {
  double sum = 0;
  for (double v : per_bin) sum += v * bin_nm;
  return sum;
}

double Light::power(double bin_nm, double radius) const {
  const double s = integrated(bin_nm);
  switch (type) {
    case LightType::point: return 4 * M_PI * s;
    // The full cone's solid angle, its falloff ring counted at half (pbrt-v4's SpotLight::Phi).
    case LightType::spot:
      return 2 * M_PI * s * ((1 - cos_falloff()) + (cos_falloff() - cos_total()) / 2);
    case LightType::distant: return M_PI * radius * radius * s;
    case LightType::infinite: return 4 * M_PI * M_PI * radius * radius * s;
  }
  return 0;
}

static Eigen::Vector3d point(const JsonNode& node) {
  auto a = node.vec3();
  for (double x : a)
    if (!(std::abs(x) <= kMaxCoordinate)) node.fail("a coordinate beyond ±1e18");
  return {a[0], a[1], a[2]};
}

// "from" and "to": the direction from one to the other (pbrt-v4's spot and distant lights).
static Eigen::Vector3d from_to(const JsonNode& node, Eigen::Vector3d* from) {
  Eigen::Vector3d f(0, 0, 0), t(0, 0, 1);
  if (auto n = node.find("from")) f = point(*n);
  if (auto n = node.find("to")) t = point(*n);
  if (from) *from = f;
  Eigen::Vector3d d = t - f;
  if (!(d.norm() > 0)) node.fail("\"from\" and \"to\" are the same point");
  return d.normalized();
}

Light parse_light(const JsonNode& node) {
  if (!node.is_object()) node.fail("expected a light object");
  Light l;
  l.where = node.file() + ": " + node.path();
  const std::string type = node.at("type").string();
  const char* key = nullptr;
  if (type == "point") {
    l.type = LightType::point;
    key = "intensity";
    if (auto p = node.find("position")) l.position = point(*p);
  } else if (type == "spot") {
    l.type = LightType::spot;
    key = "intensity";
    l.direction = from_to(node, &l.position);
    if (auto c = node.find("cone_deg")) l.cone_deg = c->number_in(1e-3, 180.0);
    if (auto c = node.find("cone_delta_deg")) l.cone_delta_deg = c->number_in(0.0, 180.0);
    if (l.cone_delta_deg > l.cone_deg)
      node.at("cone_delta_deg").fail("the falloff is wider than the cone (\"cone_deg\")");
  } else if (type == "distant") {
    l.type = LightType::distant;
    key = "irradiance";
    l.direction = from_to(node, nullptr);
  } else if (type == "infinite") {
    l.type = LightType::infinite;
    key = "radiance";
  } else {
    node.at("type").fail("unknown light type \"" + type + "\" (point, spot, distant, infinite)");
  }
  l.spectrum = parse_spectrum(node.at(key));
  if (auto s = node.find("scale")) l.scale = s->number_in(0.0, kMaxSpectrumValue);
  node.finish();
  return l;
}

}  // namespace kasha
