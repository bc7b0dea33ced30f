#include "scene/camera.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "scene/limits.h"

namespace kasha {

static Eigen::Vector3d vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

static void put(float out[3], const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(v[k]);
}

// A camera vector inside the range vertices keep to: the kernels carry it in float and square
// distances from it.
static std::array<double, 3> bounded_vec3(const JsonNode& node) {
  std::array<double, 3> a = node.vec3();
  for (double x : a)
    if (!(std::abs(x) <= kMaxCoordinate)) {
      std::ostringstream msg;
      msg << "a coordinate of " << x << " is beyond ±1e18";
      node.fail(msg.str());
    }
  return a;
}

// The camera's type and what it takes: a lens and a screen window, or a spherical mapping.
static void parse_projection(const JsonNode& node, Camera* c) {
  if (auto t = node.find("type")) {
    c->type = t->string();
    if (c->type != "perspective" && c->type != "orthographic" && c->type != "spherical")
      t->fail("\"type\" is \"perspective\", \"orthographic\" or \"spherical\"");
  }
  if (auto r = node.find("lens_radius")) {
    if (c->type != "perspective") r->fail("a lens is built for the perspective camera only");
    c->lens_radius = r->number_in(0, kMaxCoordinate);
  }
  if (auto f = node.find("focal_distance")) {
    c->focal_distance = f->number_in(0, kMaxCoordinate);
    if (!(c->focal_distance > 0)) f->fail("\"focal_distance\" must be positive");
  }
  if (auto m = node.find("mapping")) {
    if (c->type != "spherical") m->fail("\"mapping\" is the spherical camera's");
    c->mapping = m->string();
    if (c->mapping != "equalarea" && c->mapping != "equirectangular")
      m->fail("\"mapping\" is \"equalarea\" or \"equirectangular\"");
  }
  if (auto w = node.find("screen_window")) {
    if (c->type == "spherical") w->fail("the spherical camera has no screen window");
    const std::vector<double> v = w->numbers();
    if (v.size() != 4) w->fail("\"screen_window\" is [x0, x1, y0, y1]");
    for (double x : v)
      if (!(std::abs(x) <= kMaxCoordinate)) w->fail("a screen window bound beyond ±1e18");
    if (!(v[0] < v[1] && v[2] < v[3])) w->fail("\"screen_window\" needs x0 < x1 and y0 < y1");
    c->screen_window = std::array<double, 4>{v[0], v[1], v[2], v[3]};
  }
}

Camera parse_camera(const JsonNode& node) {
  Camera c;
  c.position = bounded_vec3(node.at("position"));
  c.look_at = bounded_vec3(node.at("look_at"));
  if (auto up = node.find("up")) c.up = bounded_vec3(*up);
  if (auto fov = node.find("fov_deg")) c.fov_deg = fov->number_in(1e-3, 179.0);
  if (auto w = node.find("width")) c.width = w->integer_in(1, 16384);
  if (auto h = node.find("height")) c.height = h->integer_in(1, 16384);
  if (auto m = node.find("mirror")) c.mirror = m->boolean();
  if (auto f = node.find("filter")) c.filter = parse_pixel_filter(*f);
  if (auto e = node.find("exposure")) {
    c.exposure = e->number_in(0, 1e12);
    if (!(c.exposure > 0)) e->fail("\"exposure\" must be positive");
  }
  parse_projection(node, &c);
  node.finish();
  Eigen::Vector3d forward = vec(c.look_at) - vec(c.position);
  if (forward.norm() == 0) node.fail("\"position\" and \"look_at\" are the same point");
  if (vec(c.up).norm() == 0) node.fail("\"up\" is zero");
  // Compared as directions: a tiny but valid "up" is not parallel.
  if (forward.normalized().cross(vec(c.up).normalized()).norm() < 1e-9)
    node.fail("\"up\" is parallel to the view direction");
  return c;
}

KCamera Camera::to_kernel() const {
  Eigen::Vector3d forward = (vec(look_at) - vec(position)).normalized();
  Eigen::Vector3d right = forward.cross(vec(up)).normalized();
  Eigen::Vector3d true_up = right.cross(forward);
  if (mirror) right = -right;
  KCamera k{};
  put(k.position, vec(position));
  put(k.forward, forward);
  k.width = width;
  k.height = height;
  k.lens_radius = static_cast<float>(lens_radius);
  k.focal_distance = static_cast<float>(focal_distance);
  if (type == "spherical") {
    k.type = mapping == "equirectangular" ? KASHA_CAMERA_EQUIRECTANGULAR : KASHA_CAMERA_EQUAL_AREA;
    put(k.right, right);
    put(k.up, true_up);
  } else {
    k.type = type == "orthographic" ? KASHA_CAMERA_ORTHOGRAPHIC : KASHA_CAMERA_PERSPECTIVE;
    const double t = type == "orthographic" ? 1.0 : std::tan(fov_deg * M_PI / 360.0);
    // The shorter side spans the field of view (pbrt-v4's default screen window).
    double sx = width >= height ? t * width / height : t;
    double sy = width >= height ? t : t * height / width;
    if (screen_window) {
      const std::array<double, 4>& w = *screen_window;
      sx = t * (w[1] - w[0]) / 2;
      sy = t * (w[3] - w[2]) / 2;
      k.center[0] = static_cast<float>((w[1] + w[0]) / (w[1] - w[0]));
      k.center[1] = static_cast<float>((w[3] + w[2]) / (w[3] - w[2]));
    }
    put(k.right, right * sx);
    put(k.up, true_up * sy);
  }
  filter.to_kernel(&k);
  return k;
}

}  // namespace kasha
