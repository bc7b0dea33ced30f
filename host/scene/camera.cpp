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
  double t = std::tan(fov_deg * M_PI / 360.0);
  // The shorter side spans the field of view.
  double sx = width >= height ? t * width / height : t;
  double sy = width >= height ? t : t * height / width;
  KCamera k{};
  put(k.position, vec(position));
  put(k.forward, forward);
  put(k.right, right * sx);
  put(k.up, true_up * sy);
  k.width = width;
  k.height = height;
  filter.to_kernel(&k);
  return k;
}

}  // namespace kasha
