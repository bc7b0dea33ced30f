#pragma once
// Gloss from in-plane goniometer data (columns theta_in_deg, theta_out_deg, brdf; the mirror
// direction at theta_out = theta_in). Per incidence angle, the diffuse floor is the median BRDF
// outside the cone around the mirror direction; inside it, g·p(δ) = (brdf − floor)·cos θo, where δ
// is the angle from the mirror direction and p is a lobe over solid angle, assumed symmetric about
// the mirror direction. Then g = 2π ∫ g p(δ) sin δ dδ over the cone and the profile is p.
#include <string>

#include "material/material.h"

namespace kasha {

struct GlossFit {
  GlossDesc gloss;
  double diffuse_floor = 0;  // mean over incidence angles, BRDF units (1/sr)
  int incidence_angles = 0;
};

GlossFit fit_gloss(const std::string& path, double cone_deg);

}  // namespace kasha
