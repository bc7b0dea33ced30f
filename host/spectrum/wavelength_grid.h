#pragma once
// The wavelength grid: N bins of equal width; spectra are stored as per-bin averages.
#include <optional>
#include <string>
#include <vector>

#include "spectrum/spectrum.h"

namespace kasha {

struct WavelengthGrid {
  double min_nm = 380.0;
  double bin_nm = 10.0;
  int bins = 40;

  double max_nm() const { return min_nm + bin_nm * bins; }
  double lo(int i) const { return min_nm + bin_nm * i; }
  double hi(int i) const { return min_nm + bin_nm * (i + 1); }
  double center(int i) const { return min_nm + bin_nm * (i + 0.5); }
  // Index of the bin holding `nm` ([lo, hi), the last bin also takes max_nm), or -1.
  int bin_of(double nm) const;

  // Exact average of the spectrum over each bin.
  std::vector<double> resample(const Spectrum& s) const;
  std::string describe() const;  // "380–780 nm, 40 bins of 10 nm"
};

// Visible range that every grid covers.
constexpr double kVisibleMinNm = 380.0;
constexpr double kVisibleMaxNm = 780.0;
// The automatic range never reaches below this.
constexpr double kShortestNm = 200.0;

// What a scene fixes of its grid; unset values are chosen automatically.
struct GridRequest {
  double min_nm = -1, max_nm = -1, bin_nm = 10.0;
};

// A request for bins of `bin_nm` over the automatic range (--bin-nm); none for 0 (the scene's).
std::optional<GridRequest> bins_request(double bin_nm);

// The automatic range of docs/design.md#the-wavelength-grid: the visible range, extended down to
// the shortest wavelength at which some emitter emits and some material is excited, on bin edges
// aligned with 380 nm.
WavelengthGrid choose_grid(const GridRequest& request, const std::vector<SpectralSupport>& emitters,
                           const std::vector<SpectralSupport>& excitations);

}  // namespace kasha
