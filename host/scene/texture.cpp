#include "scene/texture.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

namespace {

TextureWrap parse_wrap(const JsonNode& wrap) {
  const std::string v = wrap.string();
  if (v == "repeat") return TextureWrap::repeat;
  if (v == "clamp") return TextureWrap::clamp;
  if (v == "black") return TextureWrap::black;
  if (v == "octahedral_sphere") return TextureWrap::octahedral_sphere;
  wrap.fail("unknown wrap \"" + v + "\" (repeat, clamp, black, octahedral_sphere)");
}

// An image texture's file, its encoding, scale and inversion, its filter and wrap.
void parse_image_texture(const JsonNode& node, Texture& t) {
  t.type = TextureType::image;
  if (auto e = node.find("encoding")) {
    try {
      t.encoding = parse_color_encoding(e->string());
    } catch (const Error& err) {
      e->fail(err.what());
    }
  }
  JsonNode f = node.at("file");
  std::filesystem::path file(f.string());
  if (file.empty()) f.fail("empty file name");
  if (file.is_relative()) file = node.base_dir() / file;
  t.file = file.string();
  try {
    t.image = read_rgb_image(t.file, t.encoding);
  } catch (const Error& e) {
    f.fail(e.what());
  }
  if (auto s = node.find("scale")) t.scale = s->number_in(-1e6, 1e6);
  if (auto i = node.find("invert")) t.invert = i->boolean();
  if (t.scale != 1 || t.invert)
    for (float& v : t.image.rgb) {
      const double scaled = v * t.scale;
      v = static_cast<float>(std::max(0.0, t.invert ? 1 - scaled : scaled));
    }
  if (auto filter = node.find("filter")) {
    const std::string v = filter->string();
    if (v == "bilinear")
      t.bilinear = true;
    else if (v == "nearest")
      t.bilinear = false;
    else
      filter->fail("unknown filter \"" + v + "\" (bilinear, nearest)");
  }
  if (auto wrap = node.find("wrap")) t.wrap = parse_wrap(*wrap);
}

}  // namespace

Texture parse_texture(const JsonNode& node, const std::string& name) {
  if (!node.is_object()) node.fail("expected a texture object");
  Texture t;
  t.name = name;
  t.where = node.where();
  const std::string type = node.at("type").string();
  if (type == "image") {
    parse_image_texture(node, t);
  } else if (type == "checkerboard") {
    t.type = TextureType::checkerboard;
    JsonNode even = node.at("even"), odd = node.at("odd");
    if (even.is_number()) t.even_value = even.number();
    if (odd.is_number()) t.odd_value = odd.number();
    t.even = parse_spectrum(even);
    t.odd = parse_spectrum(odd);
  } else {
    node.at("type").fail("unknown texture type \"" + type + "\" (image, checkerboard)");
  }
  auto factor = [&](const char* key, double& out, bool scale) {
    if (auto n = node.find(key)) {
      out = n->number_in(-1e6, 1e6);
      if (scale && out == 0) n->fail("a scale of 0");
    }
  };
  factor("uscale", t.uscale, true);
  factor("vscale", t.vscale, true);
  factor("udelta", t.udelta, false);
  factor("vdelta", t.vdelta, false);
  node.finish();
  return t;
}

}  // namespace kasha
