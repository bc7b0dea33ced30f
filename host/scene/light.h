#pragma once
// Lights that are not emitting shapes (docs/lights.md): a point, a spot, a distant light and an
// infinite light, with pbrt-v4's parameters and defaults. Their spectra are physical: a point's
// and a spot's intensity (W·sr⁻¹·nm⁻¹), a distant light's irradiance on a surface facing it
// (W·m⁻²·nm⁻¹), an infinite light's radiance (W·m⁻²·sr⁻¹·nm⁻¹).
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "core/json_node.h"
#include "image/rgb_image.h"
#include "spectrum/spectrum.h"
#include "spectrum/wavelength_grid.h"

namespace kasha {

enum class LightType { point, spot, distant, infinite };

// An infinite light's environment image (docs/lights.md#environment-images): linear sRGB texels,
// each an RGB illuminant spectrum; how directions map onto it; the linear map from the scene's
// directions to the image's frame (+z up), directions normalised after it as pbrt-v4 does: the
// inverse of the light's transform, any invertible one (mirrors, scales, shears).
enum class EnvironmentMapping { latlong, equal_area };
struct EnvironmentImage {
  std::string file;
  RgbImage image;
  EnvironmentMapping mapping = EnvironmentMapping::latlong;
  Eigen::Matrix3d to_light = Eigen::Matrix3d::Identity();
  bool orthogonal = true;  // to_light is a rotation or a mirror: its inverse is its transpose
};

// What the kernels read of an environment image on the scene's grid (kernels/lights/environment.h):
// per texel the sigmoid's coefficients and scale; the sampling distribution (marginal CDF over
// rows, then each row's CDF), texels weighed by their power (mean RGB times solid angle); and the
// image's mean over the sphere of ∫L dλ relative to the light's own row (for its power).
struct EnvironmentData {
  std::vector<float> texels;        // 4 per texel
  std::vector<float> distribution;  // height + 1, then height × (width + 1)
  double mean_factor = 1;
};
EnvironmentData environment_data(const EnvironmentImage& env, const std::vector<double>& row,
                                 const WavelengthGrid& grid);

struct Light {
  LightType type = LightType::point;
  std::string where;                   // file: JSON path of the light
  SpectrumPtr spectrum;                // before "scale"
  double scale = 1;                    // on the spectrum
  std::vector<double> per_bin;         // spectrum × scale on the scene grid
  Eigen::Vector3d position{0, 0, 0};   // point, spot
  Eigen::Vector3d direction{0, 0, 1};  // spot: the cone's axis; distant: where the light travels
  double cone_deg = 30;                // spot: the cone's half-angle, where the intensity reaches 0
  double cone_delta_deg = 5;           // spot: the width of the falloff inside the cone's edge
  std::shared_ptr<const EnvironmentImage> environment;      // infinite: its image, or none
  std::shared_ptr<const EnvironmentData> environment_data;  // on the grid, set when the scene loads

  double cos_total() const;
  double cos_falloff() const;
  // Σ_i value_i·Δλ over the grid: what the light's power is proportional to.
  double integrated(double bin_nm) const;
  // The power (W) it sends into the scene; a distant or infinite light's through a disk of radius
  // `radius` (the scene's bounding sphere), as light sampling weighs it (pbrt-v4's Phi).
  double power(double bin_nm, double radius) const;
};

const char* light_type_name(LightType type);

// One entry of the scene's "lights" array.
Light parse_light(const JsonNode& node);

}  // namespace kasha
