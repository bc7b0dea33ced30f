#include "scene/light.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "scene/limits.h"
#include "scene/transform.h"
#include "spectrum/rgb_spectrum.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

const char* light_type_name(LightType type) {
  switch (type) {
    case LightType::point:
      return "point";
    case LightType::spot:
      return "spot";
    case LightType::distant:
      return "distant";
    case LightType::infinite:
      return "infinite";
  }
  return "?";
}

double Light::cos_total() const {
  return std::cos(cone_deg * M_PI / 180.0);
}
double Light::cos_falloff() const {
  return std::cos((cone_deg - cone_delta_deg) * M_PI / 180.0);
}

double Light::integrated(double bin_nm) const {
  double sum = 0;
  for (double v : per_bin) sum += v * bin_nm;
  return sum;
}

double Light::power(double bin_nm, double radius) const {
  const double s = integrated(bin_nm);
  switch (type) {
    case LightType::point:
      return 4 * M_PI * s;
    // The full cone's solid angle, its falloff ring counted at half (pbrt-v4's SpotLight::Phi).
    case LightType::spot:
      return 2 * M_PI * s * ((1 - cos_falloff()) + (cos_falloff() - cos_total()) / 2);
    case LightType::distant:
      return M_PI * radius * radius * s;
    case LightType::infinite:
      return 4 * M_PI * M_PI * radius * radius * s *
             (environment_data ? environment_data->mean_factor : 1.0);
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
  l.where = node.where();
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
    if (auto image = node.find("image")) {
      // Each texel an RGB illuminant; the light's spectrum is their white, D65 at luminance 1.
      if (node.has("radiance"))
        node.at("radiance").fail("an infinite light takes \"radiance\" or \"image\", not both");
      auto env = std::make_shared<EnvironmentImage>();
      const std::filesystem::path file = image->file_path();
      env->file = file.string();
      try {
        env->image = read_rgb_image(env->file);
      } catch (const Error& e) {
        image->fail(e.what());
      }
      if (auto m = node.find("mapping")) {
        const std::string name = m->string();
        if (name == "latlong")
          env->mapping = EnvironmentMapping::latlong;
        else if (name == "equal_area")
          env->mapping = EnvironmentMapping::equal_area;
        else
          m->fail("unknown mapping \"" + name + "\" (latlong, equal_area)");
        if (env->mapping == EnvironmentMapping::equal_area && env->image.width != env->image.height)
          m->fail("an equal-area image must be square, not " + std::to_string(env->image.width) +
                  "x" + std::to_string(env->image.height));
      }
      if (auto t = node.find("transform")) {
        const Eigen::Matrix3d r = parse_transform(*t).linear();
        // Invertible, and not so far from a rotation that float directions lose their meaning.
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r);
        const Eigen::Vector3d sv = svd.singularValues();
        if (!(sv[2] > 0) || !(sv[0] / sv[2] < 1e6))
          t->fail(
              "an infinite light's transform must be invertible (its directions' map is "
              "singular or nearly so)");
        env->orthogonal = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6;
        env->to_light = env->orthogonal ? Eigen::Matrix3d(r.transpose()) : r.inverse();
      }
      l.environment = env;
      l.spectrum = d65_luminance_one();
      key = nullptr;
    }
  } else {
    node.at("type").fail("unknown light type \"" + type + "\" (point, spot, distant, infinite)");
  }
  if (key) l.spectrum = parse_spectrum(node.at(key));
  if (auto s = node.find("scale")) l.scale = s->number_in(0.0, kMaxSpectrumValue);
  node.finish();
  return l;
}

EnvironmentData environment_data(const EnvironmentImage& env, const std::vector<double>& row,
                                 const WavelengthGrid& grid) {
  const int W = env.image.width, H = env.image.height;
  EnvironmentData d;
  d.texels.resize(size_t(4) * W * H);
  std::vector<double> weight(size_t(W) * H);
  double row_sum = 0, mean = 0;
  for (int i = 0; i < grid.bins; ++i) row_sum += row[i] * grid.bin_nm;
  for (int y = 0; y < H; ++y) {
    // The texel's solid angle: latitude-longitude rows shrink towards the poles.
    const double omega =
        env.mapping == EnvironmentMapping::equal_area
            ? 4 * M_PI / (double(W) * H)
            : 2 * M_PI / W * (std::cos(M_PI * y / H) - std::cos(M_PI * (y + 1) / H));
    for (int x = 0; x < W; ++x) {
      const float* p = env.image.at(x, y);
      double scale;
      SigmoidCoefficients c = rgb_unbounded_sigmoid({p[0], p[1], p[2]}, &scale);
      if (!(scale > 0)) c = {0, 0, 0}, scale = 0;
      const size_t t = size_t(y) * W + x;
      for (int q = 0; q < 3; ++q) d.texels[4 * t + q] = static_cast<float>(c[q]);
      d.texels[4 * t + 3] = static_cast<float>(scale);
      double integral = 0;
      if (scale > 0)
        for (int i = 0; i < grid.bins; ++i)
          integral += row[i] * scale * sigmoid_spectrum(c, grid.center(i)) * grid.bin_nm;
      mean += integral * omega / (4 * M_PI);
      weight[t] = (double(p[0]) + p[1] + p[2]) / 3 * omega;
    }
  }
  d.mean_factor = row_sum > 0 ? mean / row_sum : 0;
  // The marginal CDF over rows, then each row's CDF over its texels (uniform where all is dark).
  std::vector<double> row_weight(H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) row_weight[y] += weight[size_t(y) * W + x];
  double total = 0;
  for (double w : row_weight) total += w;
  d.distribution.push_back(0);
  double acc = 0;
  for (int y = 0; y < H; ++y) {
    acc += total > 0 ? row_weight[y] : 1;
    d.distribution.push_back(static_cast<float>(acc / (total > 0 ? total : H)));
  }
  d.distribution.back() = 1;
  for (int y = 0; y < H; ++y) {
    d.distribution.push_back(0);
    double a = 0;
    for (int x = 0; x < W; ++x) {
      a += row_weight[y] > 0 ? weight[size_t(y) * W + x] : 1;
      d.distribution.push_back(static_cast<float>(a / (row_weight[y] > 0 ? row_weight[y] : W)));
    }
    d.distribution.back() = 1;
  }
  return d;
}

}  // namespace kasha
