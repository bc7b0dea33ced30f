#include "spectrum/wavelength_grid.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kasha {

int WavelengthGrid::bin_of(double nm) const {
  if (nm < min_nm || nm > max_nm()) return -1;
  int i = static_cast<int>(std::floor((nm - min_nm) / bin_nm));
  return std::min(i, bins - 1);
}

std::vector<double> WavelengthGrid::resample(const Spectrum& s) const {
  std::vector<double> out(bins);
  for (int i = 0; i < bins; ++i) out[i] = s.integral(lo(i), hi(i)) / bin_nm;
  // A line exactly at the top edge belongs to the last bin.
  if (auto* line = dynamic_cast<const LineSpectrum*>(&s); line && line->wavelength() == max_nm())
    out[bins - 1] += s.scale() / bin_nm;
  return out;
}

std::string WavelengthGrid::describe() const {
  std::ostringstream o;
  o << min_nm << "–" << max_nm() << " nm, " << bins << " bins of " << bin_nm << " nm";
  return o.str();
}

std::optional<GridRequest> bins_request(double bin_nm) {
  if (!(bin_nm > 0)) return std::nullopt;
  GridRequest g;
  g.bin_nm = bin_nm;
  return g;
}

WavelengthGrid choose_grid(const GridRequest& request, const std::vector<SpectralSupport>& emitters,
                           const std::vector<SpectralSupport>& excitations) {
  double shortest = kVisibleMinNm;
  for (const SpectralSupport& e : emitters) {
    if (e.empty || e.unbounded) continue;
    for (const SpectralSupport& x : excitations) {
      if (x.empty) continue;
      double lo = x.unbounded ? e.lo_nm : std::max(e.lo_nm, x.lo_nm);
      double hi = x.unbounded ? e.hi_nm : std::min(e.hi_nm, x.hi_nm);
      if (lo <= hi) shortest = std::min(shortest, lo);
    }
  }
  shortest = std::max(shortest, kShortestNm);

  WavelengthGrid grid;
  grid.bin_nm = request.bin_nm;
  double lo = request.min_nm;
  if (lo < 0) {
    // Whole bins below 380 nm, so 380 nm stays a bin edge.
    double extra = std::ceil((kVisibleMinNm - shortest) / grid.bin_nm - 1e-9);
    lo = kVisibleMinNm - std::max(0.0, extra) * grid.bin_nm;
  }
  double hi = request.max_nm >= 0 ? request.max_nm : kVisibleMaxNm;
  grid.min_nm = lo;
  grid.bins = std::max(1, static_cast<int>(std::ceil((hi - lo) / grid.bin_nm - 1e-9)));
  return grid;
}

}  // namespace kasha
