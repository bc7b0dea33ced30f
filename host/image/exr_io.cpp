#include "image/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "color/color_space.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"

namespace kasha {

// OpenEXR's message repeats the file ("Cannot read image file "F". Early end of file: …"): the
// path is ours to give once, and the rest reads as the cause, in lower case.
static Error exr_failure(const std::string& path, const std::exception& e) {
  static const std::regex framing(R"(^[A-Z][^"]* image file "[^"]*"\. )");
  std::string cause = std::regex_replace(std::string(e.what()), framing, "");
  if (!cause.empty() && cause.back() == '.') cause.pop_back();
  if (cause.size() > 1 && std::isupper(static_cast<unsigned char>(cause[0])) &&
      std::islower(static_cast<unsigned char>(cause[1])))
    cause[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(cause[0])));
  return Error(printable(path) + ": cannot read EXR: " + printable(cause));
}

// The channels of the XYZ layer and of linear sRGB, in order.
static const char* const kXyzNames[3] = {"XYZ.X", "XYZ.Y", "XYZ.Z"};
static const char* const kRgbNames[3] = {"R", "G", "B"};

std::string spectral_channel_name(double nm) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", nm);
  std::string s = text;
  std::replace(s.begin(), s.end(), '.', ',');
  return "S0." + s + "nm";
}

void write_exr(const std::string& path, const Image& image,
               const std::map<std::string, std::string>& attributes) {
  const size_t n = image.pixels();
  std::vector<float> rgb(3 * n);
  for (size_t p = 0; p < n; ++p) {
    Vec3d c = xyz_to_linear_srgb({image.xyz[3 * p], image.xyz[3 * p + 1], image.xyz[3 * p + 2]});
    for (int k = 0; k < 3; ++k) rgb[3 * p + k] = static_cast<float>(c[k]);
  }
  write_atomically(path, [&](const std::string& tmp) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, value] : attributes) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer fb;
    auto add = [&](const std::string& name, const float* base, size_t stride_floats) {
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      fb.insert(name, Imf::Slice(Imf::FLOAT, (char*)base, sizeof(float) * stride_floats,
                                 sizeof(float) * stride_floats * image.width));
    };
    for (int k = 0; k < 3; ++k) add(kRgbNames[k], rgb.data() + k, 3);
    for (int k = 0; k < 3; ++k) add(kXyzNames[k], image.xyz.data() + k, 3);
    if (image.has_spectral()) {
      header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
      header.insert("emissiveUnits", Imf::StringAttribute("W.m^-2.sr^-1"));
      for (int i = 0; i < image.grid.bins; ++i)
        add(spectral_channel_name(image.grid.center(i)), image.spectral.data() + i,
            image.grid.bins);
    }
    // Our own stream, so its flush and close are checked: OpenEXR writes the offset table in
    // OutputFile's destructor and swallows errors there.
    write_stream_file(tmp, path, [&](std::ofstream& out) {
      Imf::StdOFStream stream(out, tmp.c_str());
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(fb);
      file.writePixels(image.height);
    });
  });
}

std::map<std::string, std::string> read_exr_attributes(const std::string& path) {
  check_input_file(path, kMaxBinaryInputBytes);
  try {
    Imf::InputFile file(path.c_str());
    std::map<std::string, std::string> out;
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
      if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        out[it.name()] = s->value();
    return out;
  } catch (const std::exception& e) {
    throw exr_failure(path, e);
  }
}

namespace {

// The wavelength a spectral channel's name gives ("S0.555,000000nm" -> 555), or throws naming
// the channel (escaped: the name is bytes from the file).
double channel_wavelength(const std::string& path, const std::string& name) {
  std::string value = name.substr(3, name.size() - 5);
  std::replace(value.begin(), value.end(), ',', '.');
  char* end = nullptr;
  const double nm = value.empty() || std::isspace(static_cast<unsigned char>(value[0]))
                        ? 0
                        : std::strtod(value.c_str(), &end);
  if (end != value.c_str() + value.size() || !std::isfinite(nm) || !(nm > 0))
    throw Error(printable(path) + ": channel \"" + printable(name) +
                "\": not a spectral channel name (S0.<wavelength>nm with a positive wavelength)");
  return nm;
}

// "nan", "inf" or "-inf", as the message names the value.
std::string non_finite_text(float v) {
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

// Every command that reads an image reads it here, so a NaN or infinite value is refused once,
// with its pixel (x from the left, y from the top of the data window) and channel, rather than
// averaging into "nan ± 0" or "rmse nan" downstream. `values` holds `names.size()` per pixel.
void check_finite(const std::string& path, int width, const std::vector<float>& values,
                  const std::vector<std::string>& names) {
  const size_t per_pixel = names.size();
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) {
      const size_t p = i / per_pixel;
      throw Error(printable(path) + ": pixel (" + std::to_string(p % width) + ", " +
                  std::to_string(p / width) + ") channel " + printable(names[i % per_pixel]) +
                  " is " + non_finite_text(values[i]));
    }
}

// The largest reference kasha reads: far beyond any film it renders, small enough that the
// buffers fit in memory (the file size does not bound them: EXR compresses).
constexpr double kMaxExrFloats = 1073741824.0;  // 2^30 floats, 4 GiB

// The image's size from its data window, checked before anything is allocated for it.
void set_size(const std::string& path, const Imath::Box2i& dw, Image& img) {
  // In 64 bits: a data window from a damaged header can span more than an int.
  const long long w = 1LL + dw.max.x - dw.min.x, h = 1LL + dw.max.y - dw.min.y;
  if (w <= 0 || h <= 0 || w > (1 << 20) || h > (1 << 20))
    throw Error(printable(path) + ": the data window is " + std::to_string(w) + "x" +
                std::to_string(h) + " pixels");
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
}

// The spectral channels: wavelength -> channel name.
std::map<double, std::string> spectral_channels(const std::string& path,
                                                const Imf::ChannelList& channels) {
  std::map<double, std::string> bins;
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    std::string name = it.name();
    if (name.rfind("S0.", 0) == 0 && name.size() > 5 && name.substr(name.size() - 2) == "nm") {
      const double nm = channel_wavelength(path, name);
      if (!bins.emplace(nm, name).second)
        throw Error(printable(path) + ": channels \"" + printable(bins[nm]) + "\" and \"" +
                    printable(name) + "\" hold the same wavelength");
    }
  }
  return bins;
}

// The grid the spectral channels' wavelengths describe: min + bin width, so only evenly spaced
// channels describe one.
WavelengthGrid spectral_grid(const std::string& path, const std::map<double, std::string>& bins) {
  std::vector<double> wl;
  for (const auto& [nm, name] : bins) wl.push_back(nm);
  for (size_t k = 2; k < wl.size(); ++k)
    if (std::abs((wl[k] - wl[k - 1]) - (wl[1] - wl[0])) > 1e-3 * (wl[1] - wl[0]))
      throw Error(printable(path) + ": spectral channels are not evenly spaced (" +
                  printable(bins.at(wl[k - 1])) + ", " + printable(bins.at(wl[k])) + ")");
  WavelengthGrid grid;
  grid.bins = static_cast<int>(wl.size());
  grid.bin_nm = wl.size() > 1 ? (wl.back() - wl.front()) / (wl.size() - 1) : 10.0;
  grid.min_nm = wl.front() - 0.5 * grid.bin_nm;
  return grid;
}

// Channel `channel` of `data`, `stride` floats a pixel, as a slice of the file's data window.
Imf::Slice interleaved_slice(float* data, size_t channel, size_t stride, const Imath::Box2i& dw,
                             int width) {
  char* origin = (char*)data - (dw.min.x + dw.min.y * (size_t)width) * stride * sizeof(float);
  return Imf::Slice(Imf::FLOAT, origin + channel * sizeof(float), stride * sizeof(float),
                    stride * sizeof(float) * width);
}

// XYZ from linear sRGB, `width` pixels a row. Checked in double: finite R, G, B near a float's
// limit can make an XYZ beyond it.
std::vector<float> xyz_from_rgb(const std::string& path, const std::vector<float>& rgb, int width) {
  const size_t n = rgb.size() / 3;
  std::vector<float> xyz(3 * n);
  for (size_t p = 0; p < n; ++p) {
    Vec3d c = linear_srgb_to_xyz({rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]});
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(c[k]) <= std::numeric_limits<float>::max()))
        throw Error(printable(path) + ": pixel (" + std::to_string(p % width) + ", " +
                    std::to_string(p / width) + "): R, G, B give an XYZ beyond a float's range");
    for (int k = 0; k < 3; ++k) xyz[3 * p + k] = static_cast<float>(c[k]);
  }
  return xyz;
}

}  // namespace

Image read_exr(const std::string& path) {
  check_input_file(path, kMaxBinaryInputBytes);
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    Image img;
    img.source = path;
    set_size(path, dw, img);
    const size_t n = img.pixels();
    const Imf::ChannelList& channels = file.header().channels();
    const std::map<double, std::string> bins = spectral_channels(path, channels);
    if (double(img.width) * img.height * (3 + bins.size()) > kMaxExrFloats)
      throw Error(printable(path) + ": the image is " + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + " with " + std::to_string(3 + bins.size()) +
                  " channels, beyond what kasha reads as a reference");
    bool has_xyz = channels.findChannel("XYZ.X") && channels.findChannel("XYZ.Y") &&
                   channels.findChannel("XYZ.Z");
    bool has_rgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!has_xyz && !has_rgb)
      throw Error(printable(path) + ": EXR has neither an XYZ layer nor R, G, B channels");
    const char* const* names = has_xyz ? kXyzNames : kRgbNames;

    std::vector<float> three(3 * n, 0.0f);
    Imf::FrameBuffer fb;
    for (int k = 0; k < 3; ++k)
      fb.insert(names[k], interleaved_slice(three.data(), k, 3, dw, img.width));
    std::vector<std::string> spectral_names;
    if (!bins.empty()) {
      img.grid = spectral_grid(path, bins);
      img.spectral.assign(n * bins.size(), 0.0f);
      for (const auto& [nm, name] : bins) {
        fb.insert(name, interleaved_slice(img.spectral.data(), spectral_names.size(), bins.size(),
                                          dw, img.width));
        spectral_names.push_back(name);
      }
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    check_finite(path, img.width, three, std::vector<std::string>(names, names + 3));
    if (!bins.empty()) check_finite(path, img.width, img.spectral, spectral_names);
    img.xyz = has_xyz ? std::move(three) : xyz_from_rgb(path, three, img.width);
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw exr_failure(path, e);
  }
}

}  // namespace kasha
