#pragma once
// pbrt-v4's spectrum parameters (`rgb`, `blackbody`, `spectrum [λ v …]`, a named spectrum, a
// spectrum file, a float) as kasha spectrum values (docs/formats.md#spectrum-values), and the
// photometric normalisation pbrt-v4 gives light spectra.
#include <array>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "scene/pbrt/pbrt_parameters.h"
#include "spectrum/spectrum.h"

namespace kasha {

// How pbrt-v4 reads the spectrum (its SpectrumType, chosen per parameter): a reflectance (rgb in
// [0, 1]: Jakob–Hanika's sigmoid), a quantity without bounds (an index: rgb as pbrt-v4's
// RGBUnboundedSpectrum) or an emitter (rgb as an RGB illuminant).
enum class PbrtSpectrumUse { kAlbedo, kUnbounded, kIlluminant };

// The range pbrt-v4 samples wavelengths in; spectra the importer computes are tabulated over it.
constexpr int kPbrtTableMinNm = 360, kPbrtTableMaxNm = 830;

// f tabulated every nanometre over kPbrtTableMinNm–kPbrtTableMaxNm as a kasha spectrum value,
// its end values held beyond (1 nm to 10⁵ nm).
nlohmann::json pbrt_tabulated(const std::function<double(double)>& f);

// pbrt-v4's RGBUnboundedSpectrum of a linear sRGB triple (components ≥ 0): 2m · S(c(rgb / 2m)),
// m the largest component.
nlohmann::json pbrt_rgb_unbounded(const std::array<double, 3>& rgb);

// `p`'s value as a kasha spectrum value; relative file names resolve against `base_dir`.
nlohmann::json pbrt_spectrum(const PbrtParameter& p, PbrtSpectrumUse use,
                             const std::filesystem::path& base_dir);

// A kasha spectrum value the importer made from the statement at `where`, as a spectrum it can
// evaluate; what is wrong with it is an error at `where`.
SpectrumPtr pbrt_parse_spectrum(const nlohmann::json& kasha_spectrum,
                                const std::filesystem::path& base_dir, const PbrtLocation& where);

// ∫ ȳ(λ) s(λ) dλ as pbrt-v4's SpectrumToPhotometric computes it (1 nm steps over 360–830 nm),
// for an RGB illuminant of its illuminant alone (D65).
double pbrt_photometric(const nlohmann::json& kasha_spectrum, const std::filesystem::path& base_dir,
                        const PbrtLocation& where);

// A light's spectrum as pbrt-v4 makes it: `p` (or D65 when absent) times `scale`, divided by
// its photometric integral, so that `scale` is its luminance-like "nits" (docs/pbrt-import.md).
nlohmann::json pbrt_light_spectrum(const PbrtParameter* p, double scale,
                                   const std::filesystem::path& base_dir);

// The factor pbrt-v4 divides an RGB-illuminant light (and an environment image) by: the
// photometric integral of its D65.
double pbrt_d65_photometric();

}  // namespace kasha
