#pragma once
// Colorimetry of one material in open geometry — the whole hemisphere above it radiates one lamp's
// spectrum and nothing else is there — as a 45°/0° instrument or a light booth without walls sees
// it: per illuminant the total radiance factor β, XYZ relative to a perfect white diffuser at
// Y = 100 (CIE 15), CIELAB, CIE whiteness and tint, and, optionally, the same for the "as is"
// material with ΔE2000 between the two. The gloss lobe is left out (no specular light at 45°/0°).
#include <optional>
#include <string>
#include <vector>

#include "color/cie_observer.h"
#include "colorimetry/as_is_material.h"
#include "colorimetry/radiance_factor.h"
#include "colorimetry/whiteness.h"

namespace kasha {

struct NamedSpectrum {
  std::string label;  // as given (a built-in name, a file, a JSON value)
  SpectrumPtr spectrum;
  std::string where;  // for messages (the command-line option); the label when empty
};

struct ColorimetryRequest {
  MaterialDesc material;
  std::vector<NamedSpectrum> illuminants;
  Observer observer = Observer::cie1931_2deg;
  double bin_nm = 10;
  std::optional<NamedSpectrum> as_is_lamp;
};

struct AsIsColour {
  Vec3d xyz, lab;
  double delta_e00 = 0;  // against the fluorescent material under the same illuminant
};

struct IlluminantColorimetry {
  std::string illuminant;
  std::vector<double> lamp;  // S per bin
  RadianceFactor beta;
  Vec3d white, xyz, lab;  // white: the perfect diffuser, Y = 100
  Whiteness whiteness;
  std::optional<AsIsColour> as_is;
};

struct Colorimetry {
  WavelengthGrid grid;
  Observer observer = Observer::cie1931_2deg;
  Material material;
  std::vector<IlluminantColorimetry> illuminants;
  std::optional<AsIsMaterial> as_is;
};

// One grid for every illuminant: `bin_nm` bins over 380–780 nm, extended down
// (docs/design.md#the-wavelength-grid) to the shortest wavelength at which some illuminant (or the
// as-is lamp) emits and the material is excited. Throws kasha::Error for an illuminant (or as-is
// lamp) the observer cannot see at all, for one under which the white's X or Z is 0 (no CIELAB),
// and for any result that would not be finite.
Colorimetry evaluate_colorimetry(const ColorimetryRequest& request);

// XYZ of the radiance `leaving` a surface under `lamp` (both per bin), scaled so that a perfect
// white diffuser under the lamp has Y = 100; `label` names the lamp in the error when it has no
// light the observer sees.
Vec3d relative_xyz(const BinnedObserver& observer, const std::vector<double>& leaving,
                   const std::vector<double>& lamp, double bin_nm, const std::string& label);

}  // namespace kasha
