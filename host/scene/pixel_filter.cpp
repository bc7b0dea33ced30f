#include "scene/pixel_filter.h"

#include <cmath>

namespace kasha {

bool is_pixel_filter(const std::string& type) {
  return type == "box" || type == "triangle" || type == "gaussian" || type == "mitchell" ||
         type == "lanczos";
}

PixelFilter default_pixel_filter(const std::string& type) {
  PixelFilter f;
  f.type = type;
  if (type == "gaussian") f.radius = {1.5, 1.5};
  if (type == "triangle" || type == "mitchell") f.radius = {2, 2};
  if (type == "lanczos") f.radius = {4, 4};
  return f;
}

static double sinc(double x) {
  return std::abs(x) < 1e-5 ? 1 - x * x * M_PI * M_PI / 6 : std::sin(M_PI * x) / (M_PI * x);
}

static double mitchell(double x, double b, double c) {
  x = std::abs(x);
  if (x <= 1)
    return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
  if (x <= 2)
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
            (8 * b + 24 * c)) /
           6;
  return 0;
}

double PixelFilter::evaluate_1d(int axis, double x) const {
  const double r = radius[axis];
  if (std::abs(x) > r) return 0;
  if (type == "triangle") return r - std::abs(x);
  if (type == "gaussian") {
    auto g = [&](double t) { return std::exp(-t * t / (2 * sigma * sigma)); };
    return std::max(0.0, g(x) - g(r));
  }
  if (type == "mitchell") return mitchell(2 * x / r, b, c);
  if (type == "lanczos") return sinc(x) * sinc(x / tau);
  return 1;
}

void PixelFilter::to_kernel(KCamera* out) const {
  out->filter = type.empty()         ? KASHA_FILTER_PIXEL
                : type == "box"      ? KASHA_FILTER_BOX
                : type == "triangle" ? KASHA_FILTER_TRIANGLE
                                     : KASHA_FILTER_TABLE;
  for (int axis = 0; axis < 2; ++axis) {
    out->filter_radius[axis] = static_cast<float>(radius[axis]);
    // The positive part's mass per bin of the half axis, by the midpoint rule on 64 points a bin.
    const int steps = 64;
    std::array<double, KASHA_FILTER_BINS> mass{};
    double total = 0;
    for (int b = 0; b < KASHA_FILTER_BINS; ++b) {
      for (int k = 0; k < steps; ++k) {
        double x = radius[axis] * (b + (k + 0.5) / steps) / KASHA_FILTER_BINS;
        mass[b] += std::max(0.0, evaluate_1d(axis, x));
      }
      total += mass[b];
    }
    double run = 0;
    for (int b = 0; b < KASHA_FILTER_BINS; ++b) {
      run += mass[b];
      out->filter_cdf[axis][b] =
          b == KASHA_FILTER_BINS - 1 ? 1.0f : static_cast<float>(total > 0 ? run / total : 1);
    }
  }
}

PixelFilter parse_pixel_filter(const JsonNode& node) {
  const JsonNode type_node = node.at("type");
  const std::string type = type_node.string();
  if (!is_pixel_filter(type))
    type_node.fail("\"" + type +
                   "\" is not a pixel filter (box, triangle, gaussian, mitchell, lanczos)");
  PixelFilter f = default_pixel_filter(type);
  if (auto r = node.find("radius")) {
    std::vector<double> v = r->numbers();
    if (v.size() != 2) r->fail("takes two radii, x and y, in pixels");
    for (int axis = 0; axis < 2; ++axis) {
      if (!(v[axis] > 0 && v[axis] <= KASHA_FILTER_MAX_RADIUS))
        r->fail("a radius must be above 0 and at most " + std::to_string(KASHA_FILTER_MAX_RADIUS) +
                " pixels");
      f.radius[axis] = v[axis];
    }
  }
  if (auto s = node.find("sigma")) f.sigma = s->number_in(1e-3, 1e3);
  if (auto b = node.find("B")) f.b = b->number_in(-1e3, 1e3);
  if (auto c = node.find("C")) f.c = c->number_in(-1e3, 1e3);
  if (auto t = node.find("tau")) f.tau = t->number_in(1e-3, 1e3);
  node.finish();
  return f;
}

}  // namespace kasha
