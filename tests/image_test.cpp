// Images: EXR channels, names and values as docs/formats.md#images fixes them; the film;
// whole-or-nothing writes.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "color/color_space.h"
#include "film/film.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "test_support.h"

using namespace kasha;

TEST(Exr, SpectralChannelNamesFollowTheSpectralLayout) {
  EXPECT_EQ(spectral_channel_name(555.0), "S0.555,000000nm");
  EXPECT_EQ(spectral_channel_name(382.5), "S0.382,500000nm");
}

TEST(Exr, SpectralImageReadsBackWithNamesAndValues) {
  Image img;
  img.width = 3;
  img.height = 2;
  img.grid = WavelengthGrid{550, 10, 3};  // bins centred at 555, 565, 575 nm
  for (size_t p = 0; p < img.pixels(); ++p) {
    for (int k = 0; k < 3; ++k) img.xyz.push_back(static_cast<float>(p + 0.1 * k));
    for (int i = 0; i < 3; ++i) img.spectral.push_back(static_cast<float>(100 * p + i + 0.25));
  }
  std::string path = (test::scratch_dir() / "s.exr").string();
  write_exr(path, img);

  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  for (const char* name : {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z", "S0.555,000000nm",
                           "S0.565,000000nm", "S0.575,000000nm"})
    EXPECT_NE(h.channels().findChannel(name), nullptr) << name;
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("spectralLayoutVersion").value(), "1.0");
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("emissiveUnits").value(), "W.m^-2.sr^-1");

  Image back = read_exr(path);
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  EXPECT_EQ(back.xyz, img.xyz);
  EXPECT_EQ(back.spectral, img.spectral);
  EXPECT_DOUBLE_EQ(back.grid.min_nm, 550);
  EXPECT_EQ(back.grid.bins, 3);
}

TEST(Exr, RgbIsLinearSrgbOfXyz) {
  Image img;
  img.width = img.height = 1;
  img.xyz = {0.9505f, 1.0f, 1.089f};  // D65 white, Y = 1
  std::string path = (test::scratch_dir() / "w.exr").string();
  write_exr(path, img);
  Imf::InputFile file(path.c_str());
  float rgb[3];
  Imf::FrameBuffer fb;
  const char* names[3] = {"R", "G", "B"};
  for (int k = 0; k < 3; ++k)
    fb.insert(names[k],
              Imf::Slice(Imf::FLOAT, (char*)&rgb[k], 3 * sizeof(float), 3 * sizeof(float)));
  file.setFrameBuffer(fb);
  file.readPixels(0, 0);
  for (float c : rgb) EXPECT_NEAR(c, 1.0f, 2e-3f);
  EXPECT_FALSE(file.header().channels().findChannel("S0.555,000000nm"));
}

// Every command that reads an image reads it here: a NaN or infinite value is refused with its
// pixel (x from the left, y from the top) and channel, rather than becoming "nan ± 0" downstream.
TEST(Exr, NonFinitePixelsAreRefusedWithThePixelAndChannel) {
  Image img;
  img.width = 3;
  img.height = 2;
  img.grid = WavelengthGrid{550, 10, 2};
  img.xyz.assign(3 * img.pixels(), 0.5f);
  img.spectral.assign(2 * img.pixels(), 0.25f);
  const std::string dir = test::scratch_dir().string();
  Image nan = img;
  nan.xyz[3 * (1 * 3 + 2) + 1] = std::nanf("");  // pixel (2, 1), Y
  write_exr(dir + "/nan.exr", nan);
  EXPECT_EQ(test::error_of([&] { read_exr(dir + "/nan.exr"); }),
            dir + "/nan.exr: pixel (2, 1) channel XYZ.Y is nan");
  Image inf = img;
  inf.spectral[2 * (0 * 3 + 1) + 1] = -std::numeric_limits<float>::infinity();  // (1, 0), 565 nm
  write_exr(dir + "/inf.exr", inf);
  EXPECT_EQ(test::error_of([&] { read_exr(dir + "/inf.exr"); }),
            dir + "/inf.exr: pixel (1, 0) channel S0.565,000000nm is -inf");

  // An RGB-only file names its own channel; finite R, G, B whose XYZ overflows a float too.
  auto write_rgb = [&](const std::string& path, float r, float g, float b) {
    Imf::Header header(1, 1);
    float rgb[3] = {r, g, b};
    Imf::FrameBuffer fb;
    const char* names[3] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k) {
      header.channels().insert(names[k], Imf::Channel(Imf::FLOAT));
      fb.insert(names[k],
                Imf::Slice(Imf::FLOAT, (char*)&rgb[k], 3 * sizeof(float), 3 * sizeof(float)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(1);
  };
  write_rgb(dir + "/rgb.exr", 0.5f, std::numeric_limits<float>::infinity(), 0.5f);
  EXPECT_EQ(test::error_of([&] { read_exr(dir + "/rgb.exr"); }),
            dir + "/rgb.exr: pixel (0, 0) channel G is inf");
  const float big = std::numeric_limits<float>::max();
  write_rgb(dir + "/big.exr", big, big, big);
  EXPECT_NE(test::error_of([&] {
              read_exr(dir + "/big.exr");
            }).find(dir + "/big.exr: pixel (0, 0): R, G, B give an XYZ beyond a float"),
            std::string::npos);
}

TEST(Film, AveragesPassesAndDerivesXyzFromBins) {
  WavelengthGrid g{380, 10, 40};
  Film film(2, 1, g, true);
  PassResult pass;
  pass.samples = 2;
  pass.sums.assign(2 * 40, 0.0);
  pass.sums[17] = 4.0;  // pixel 0, bin 17: two samples of 2
  pass.counters.rejected_samples = 1;
  film.accumulate(pass);
  pass.sums.assign(2 * 40, 0.0);
  film.accumulate(pass);
  Image img = film.image();
  EXPECT_FLOAT_EQ(img.spectral[17], 1.0f);
  BinnedObserver obs(g);
  EXPECT_NEAR(img.xyz[1], obs.y[17] * 10.0, 1e-6);
  EXPECT_EQ(img.xyz[4], 0.0f);
  EXPECT_EQ(film.counters().rejected_samples, 2.0);
}

TEST(Film, AddsTheIntegratorsKeptImageToTheSumsMean) {
  // Photon mapping keeps its image on the device: the film adds the latest one handed to it.
  WavelengthGrid g{380, 10, 40};
  Film film(2, 1, g, false);
  int reads = 0;
  for (float scale : {1.0f, 3.0f}) {
    PassResult p;
    p.samples = 1;
    p.sums = {1.0, 2.0, 3.0, 0.0, 0.0, 0.0};
    p.kept = [&reads, scale] {
      ++reads;
      return std::vector<float>{scale, 0, 0, 0, 0, 2 * scale};
    };
    film.accumulate(p);
  }
  EXPECT_EQ(reads, 0);  // read only when the image is wanted
  Image img = film.image();
  EXPECT_EQ(reads, 1);
  EXPECT_NEAR(img.xyz[0], 1.0 + 3.0, 1e-6);
  EXPECT_NEAR(img.xyz[1], 2.0, 1e-6);
  EXPECT_NEAR(img.xyz[5], 6.0, 1e-6);
}

TEST(Output, FailedWritesLeaveNothingBehind) {
  Image img;
  img.width = img.height = 1;
  img.xyz = {1, 1, 1};
  std::string missing_dir = (test::scratch_dir() / "no" / "such" / "x.exr").string();
  EXPECT_NE(test::error_of([&] { write_exr(missing_dir, img); }).find("does not exist"),
            std::string::npos);
  std::string png = (test::scratch_dir() / "p.png").string();
  write_png_preview(png, img);
  EXPECT_TRUE(std::filesystem::exists(png));
  size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(test::scratch_dir()))
    files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left next to it
}
