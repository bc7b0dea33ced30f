#include "colorimetry/sample_colorimetry.h"

#include <cmath>

#include "colorimetry/cie_lab.h"
#include "colorimetry/ciede2000.h"
#include "core/error.h"

namespace kasha {

Vec3d relative_xyz(const BinnedObserver& observer, const std::vector<double>& leaving,
                   const std::vector<double>& lamp, double bin_nm, const std::string& label) {
  const double white_y = observer.xyz(lamp, bin_nm)[1];
  if (!(white_y > 0))
    throw Error(label + ": the illuminant has no light the observer sees, so XYZ relative to a " +
                "perfect white (Y = 100) is undefined");
  auto xyz = observer.xyz(leaving, bin_nm);
  return {100 * xyz[0] / white_y, 100 * xyz[1] / white_y, 100 * xyz[2] / white_y};
}

// CIELAB divides by the white's X, Y and Z (CIE 15 §8.2.1): a lamp with no light under one of the
// observer's functions (a line at 700 nm has Z = 0) has no CIELAB, rather than b* = −inf.
static void check_lab_white(const Vec3d& white, const std::string& where) {
  const char* names[3] = {"X", "Y", "Z"};
  const char* functions[3] = {"x̄", "ȳ", "z̄"};
  for (int k = 0; k < 3; ++k)
    if (!(white[k] > 0))
      throw Error(where + ": the perfect white's " + names[k] +
                  " is 0 under this illuminant (no light the observer's " + functions[k] +
                  " sees), so CIELAB is undefined");
}

// A last guard: whatever the spectra, no NaN or infinity is reported as a result.
static void check_finite(const IlluminantColorimetry& r, const std::string& where) {
  std::vector<double> v = {r.xyz[0], r.xyz[1], r.xyz[2],      r.lab[0],
                           r.lab[1], r.lab[2], r.whiteness.w, r.whiteness.t};
  if (r.as_is)
    for (double x : {r.as_is->xyz[0], r.as_is->xyz[1], r.as_is->xyz[2], r.as_is->lab[0],
                     r.as_is->lab[1], r.as_is->lab[2], r.as_is->delta_e00})
      v.push_back(x);
  for (double x : v)
    if (!std::isfinite(x))
      throw Error(where +
                  ": the colorimetry under this illuminant is not finite (a spectrum too "
                  "extreme for double precision)");
}

static std::vector<double> passive_leaving(const std::vector<double>& rho,
                                           const std::vector<double>& lamp) {
  std::vector<double> out(lamp.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = rho[i] * lamp[i];
  return out;
}

Colorimetry evaluate_colorimetry(const ColorimetryRequest& q) {
  if (q.illuminants.empty()) throw Error("colorimetry: no illuminant");
  std::vector<SpectralSupport> emitting, exciting;
  for (const NamedSpectrum& s : q.illuminants) emitting.push_back(s.spectrum->support());
  if (q.as_is_lamp) emitting.push_back(q.as_is_lamp->spectrum->support());
  if (q.material.excitation) exciting.push_back(q.material.excitation->support());
  GridRequest grid_request;
  grid_request.bin_nm = q.bin_nm;

  Colorimetry c;
  c.grid = choose_grid(grid_request, emitting, exciting);
  c.observer = q.observer;
  c.material = discretize_material(q.material, c.grid);
  const BinnedObserver observer(c.grid, q.observer);
  if (q.as_is_lamp) {
    // The same check as an illuminant's: a lamp the observer cannot see makes no "as is" material.
    const std::vector<double> lamp = c.grid.resample(*q.as_is_lamp->spectrum);
    relative_xyz(observer, lamp, lamp, c.grid.bin_nm,
                 q.as_is_lamp->where.empty() ? q.as_is_lamp->label : q.as_is_lamp->where);
    c.as_is = as_is_material(c.material, lamp, c.grid, q.as_is_lamp->label);
  }

  for (const NamedSpectrum& s : q.illuminants) {
    IlluminantColorimetry r;
    r.illuminant = s.label;
    r.lamp = c.grid.resample(*s.spectrum);
    r.beta = radiance_factor(c.material, r.lamp);
    const std::string where = s.where.empty() ? s.label : s.where;
    r.white = relative_xyz(observer, r.lamp, r.lamp, c.grid.bin_nm, where);
    r.xyz =
        relative_xyz(observer, leaving_radiance(c.material, r.lamp), r.lamp, c.grid.bin_nm, where);
    check_lab_white(r.white, where);
    r.lab = xyz_to_lab(r.xyz, r.white);
    r.whiteness = cie_whiteness(r.xyz, r.white, q.observer);
    if (c.as_is) {
      AsIsColour a;
      a.xyz = relative_xyz(observer, passive_leaving(c.as_is->reflectance, r.lamp), r.lamp,
                           c.grid.bin_nm, where);
      a.lab = xyz_to_lab(a.xyz, r.white);
      a.delta_e00 = ciede2000(r.lab, a.lab);
      r.as_is = a;
    }
    check_finite(r, where);
    c.illuminants.push_back(r);
  }
  return c;
}

}  // namespace kasha
