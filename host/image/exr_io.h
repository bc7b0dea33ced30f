#pragma once
// OpenEXR images as docs/formats.md#images fixes them: linear sRGB channels R, G, B; an XYZ layer
// (XYZ.X, XYZ.Y, XYZ.Z); with a spectral film, one channel per bin named after the spectral OpenEXR
// layout (Fichet, Pacanowski, Wilkie, JCGT 2021): "S0.555,000000nm", radiance in W·m⁻²·sr⁻¹·nm⁻¹.
#include <map>
#include <string>

#include "film/image.h"

namespace kasha {

// "S0.555,000000nm" for a bin centred at 555 nm.
std::string spectral_channel_name(double wavelength_nm);

// `attributes` become string attributes of the header (provenance of references).
void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes = {});
// The string attributes of an EXR's header.
std::map<std::string, std::string> read_exr_attributes(const std::string& path);
// Reads what write_exr writes (XYZ from the XYZ layer, or from R,G,B when it is absent; spectral
// channels when present, on the grid their names give). Throws kasha::Error naming the pixel and
// channel of a value that is not finite: no command measures or shows a NaN.
Image read_exr(const std::string& path);

}  // namespace kasha
