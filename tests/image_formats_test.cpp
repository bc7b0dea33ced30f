// The image formats scenes read (host/image/rgb_image.h), against the values written here: PFM
// (both byte orders, its scale, rows from the bottom), TGA and PNG through stb_image with
// pbrt-v4's encodings (sRGB by the exact transfer function, linear, "gamma G"), Radiance HDR
// within its 8-bit mantissa, QOI by its header's colour space; and hostile files (truncated,
// sizes beyond the limit) refused with one line naming the file, before anything large is
// allocated.
#include <gtest/gtest.h>
#include <qoi.h>
#include <stb_image_write.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "image/color_encoding.h"
#include "image/rgb_image.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

namespace {

double srgb_to_linear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

std::string scratch(const std::string& name) {
  return (scratch_dir() / name).string();
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A PFM of `values` (row 0 the bottom, as the format stores it) in either byte order.
std::string pfm(const char* magic, int w, int h, double scale, const std::vector<float>& values,
                bool little) {
  std::string out = std::string(magic) + "\n" + std::to_string(w) + " " + std::to_string(h) + "\n" +
                    std::to_string(little ? -scale : scale) + "\n";
  for (float v : values) {
    unsigned char b[4];
    std::memcpy(b, &v, 4);  // the host is little endian
    if (!little) std::swap(b[0], b[3]), std::swap(b[1], b[2]);
    out.append(reinterpret_cast<char*>(b), 4);
  }
  return out;
}

// The error read_rgb_image gives, or "" when it reads the file.
std::string read_error(const std::string& path, const ColorEncoding& e = {}) {
  try {
    read_rgb_image(path, e);
  } catch (const Error& err) {
    return err.what();
  }
  return "";
}

void expect_one_line_about(const std::string& path, const std::string& error) {
  EXPECT_EQ(error.rfind(path, 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(ImageFormats, APfmIsReadInEitherByteOrderScaledAndFromTheBottomRow) {
  // 2 × 2 RGB: the file's first row is the image's bottom row.
  const std::vector<float> v = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  for (bool little : {true, false}) {
    const std::string path = scratch(little ? "le.pfm" : "be.pfm");
    write_bytes(path, pfm("PF", 2, 2, 0.5, v, little));
    const RgbImage img = read_rgb_image(path);
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 2);
    EXPECT_FLOAT_EQ(img.at(0, 1)[0], 0.5f);  // bottom left
    EXPECT_FLOAT_EQ(img.at(1, 1)[2], 3.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0)[1], 4.0f);  // top left
  }
  const std::string grey = scratch("grey.pfm");
  write_bytes(grey, pfm("Pf", 1, 1, 1, {-0.5f}, true));
  EXPECT_FLOAT_EQ(read_rgb_image(grey).at(0, 0)[1], 0.0f);  // negatives count as 0
  write_bytes(grey, pfm("Pf", 1, 1, 1, {0.25f}, true));
  EXPECT_FLOAT_EQ(read_rgb_image(grey).at(0, 0)[2], 0.25f);
}

TEST(ImageFormats, EightBitFormatsDecodeByPbrtV4sEncodings) {
  const unsigned char px[6] = {0, 10, 128, 200, 255, 64};  // 2 × 1 RGB
  const std::string tga = scratch("t.tga"), png = scratch("t.png");
  ASSERT_TRUE(stbi_write_tga(tga.c_str(), 2, 1, 3, px));
  ASSERT_TRUE(stbi_write_png(png.c_str(), 2, 1, 3, px, 6));
  ColorEncoding linear, gamma;
  linear.kind = ColorEncoding::Kind::linear;
  gamma = parse_color_encoding("gamma 2.2");
  for (int i = 0; i < 6; ++i) {
    const double v = px[i] / 255.0;
    EXPECT_NEAR(read_rgb_image(tga).rgb[i], srgb_to_linear(v), 1e-6);
    EXPECT_NEAR(read_rgb_image(png).rgb[i], srgb_to_linear(v), 1e-6);
    EXPECT_NEAR(read_rgb_image(png, linear).rgb[i], v, 1e-6);
    EXPECT_NEAR(read_rgb_image(png, gamma).rgb[i], std::pow(v, 2.2), 1e-6);
    // pbrt-v4 applies an encoding to PNGs only: a TGA stays sRGB.
    EXPECT_NEAR(read_rgb_image(tga, linear).rgb[i], srgb_to_linear(v), 1e-6);
  }
  EXPECT_THROW(parse_color_encoding("gamma"), Error);
  EXPECT_THROW(parse_color_encoding("gamma 0"), Error);
  EXPECT_THROW(parse_color_encoding("srgb"), Error);
}

TEST(ImageFormats, HdrAndQoiAreReadAsPbrtV4ReadsThem) {
  const float f[6] = {0.5f, 3.0f, 120.0f, 0.01f, 1.0f, 0.0f};
  const std::string hdr = scratch("t.hdr");
  ASSERT_TRUE(stbi_write_hdr(hdr.c_str(), 2, 1, 3, f));
  const RgbImage h = read_rgb_image(hdr);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(h.rgb[i], f[i], 0.01 * std::max(f[0], f[i]));
  const unsigned char px[6] = {0, 10, 128, 200, 255, 64};
  for (unsigned char space : {QOI_SRGB, QOI_LINEAR}) {
    qoi_desc desc{2, 1, 3, space};
    int size = 0;
    void* bytes = qoi_encode(px, &desc, &size);
    ASSERT_NE(bytes, nullptr);
    const std::string path = scratch("t.qoi");
    write_bytes(path, std::string(static_cast<char*>(bytes), size));
    std::free(bytes);
    const RgbImage q = read_rgb_image(path);
    for (int i = 0; i < 6; ++i) {
      const double v = px[i] / 255.0;
      EXPECT_NEAR(q.rgb[i], space == QOI_SRGB ? srgb_to_linear(v) : v, 1e-6);
    }
  }
}

TEST(ImageFormats, HostileFilesAreRefusedWithOneLine) {
  // Sizes beyond 2^27 pixels, checked from the header before the pixels are allocated.
  const std::string big_pfm = scratch("big.pfm");
  write_bytes(big_pfm, "PF\n100000 100000\n-1\n");
  EXPECT_NE(read_error(big_pfm).find("pixels"), std::string::npos);
  std::string tga(18, '\0');  // an uncompressed 24-bit TGA header claiming 65535 × 65535
  tga[2] = 2;
  tga[12] = tga[13] = tga[14] = tga[15] = '\xff';
  tga[16] = 24;
  const std::string big_tga = scratch("big.tga");
  write_bytes(big_tga, tga + std::string(64, '\x7f'));
  EXPECT_NE(read_error(big_tga).find("pixels"), std::string::npos);
  // Within the limit but beyond what the file's bytes can hold (stb would fill it with zeros).
  tga[12] = tga[14] = '\x40';  // 8000 × 8000
  tga[13] = tga[15] = '\x1f';
  write_bytes(big_tga, tga + std::string(64, '\x7f'));
  EXPECT_NE(read_error(big_tga).find("bytes can hold"), std::string::npos) << read_error(big_tga);
  std::string qoi = "qoif";
  for (unsigned char c : {0, 0, 0x1f, 0x40, 0, 0, 0x1f, 0x40, 3, 0}) qoi += static_cast<char>(c);
  const std::string big_qoi = scratch("big.qoi");
  write_bytes(big_qoi, qoi + std::string(64, '\xfd'));
  EXPECT_NE(read_error(big_qoi).find("bytes can hold"), std::string::npos) << read_error(big_qoi);
  // Truncated files of every format, and a PFM whose header is not numbers or not finite.
  const unsigned char px[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const float f[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  ASSERT_TRUE(stbi_write_png(scratch("whole.png").c_str(), 2, 2, 3, px, 6));
  ASSERT_TRUE(stbi_write_tga(scratch("whole.tga").c_str(), 2, 2, 3, px));
  ASSERT_TRUE(stbi_write_hdr(scratch("whole.hdr").c_str(), 2, 2, 3, f));
  write_bytes(scratch("whole.pfm"), pfm("PF", 2, 2, 1, std::vector<float>(f, f + 12), true));
  for (const char* ext : {"png", "tga", "hdr", "pfm"}) {
    const std::string bytes = file_bytes(scratch(std::string("whole.") + ext));
    for (size_t keep : {size_t(0), size_t(5), bytes.size() / 2, bytes.size() - 1}) {
      const std::string path = scratch("cut" + std::to_string(keep) + "." + ext);
      write_bytes(path, bytes.substr(0, keep));
      const std::string error = read_error(path);
      SCOPED_TRACE(path);
      // stb_image reads a PNG without its end chunk, and the last pixel of a TGA or HDR as 0.
      if (std::string(ext) != "pfm" && keep == bytes.size() - 1 && error.empty()) continue;
      expect_one_line_about(path, error);
    }
  }
  const std::string nan = scratch("nan.pfm");
  write_bytes(nan, pfm("Pf", 1, 1, 1, {std::nanf("")}, true));
  expect_one_line_about(nan, read_error(nan));
  write_bytes(nan, "PF\n2 x\n-1\n");
  expect_one_line_about(nan, read_error(nan));
}

}  // namespace
