#include "scene/texture.h"

#include <filesystem>

#include "core/error.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

Texture parse_texture(const JsonNode& node, const std::string& name) {
  if (!node.is_object()) node.fail("expected a texture object");
  Texture t;
  t.name = name;
  t.where = node.where();
  const std::string type = node.at("type").string();
  if (type == "image") {
    t.type = TextureType::image;
    JsonNode f = node.at("file");
    std::filesystem::path file(f.string());
    if (file.empty()) f.fail("empty file name");
    if (file.is_relative()) file = node.base_dir() / file;
    t.file = file.string();
    try {
      t.image = read_rgb_image(t.file);
    } catch (const Error& e) {
      f.fail(e.what());
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
    if (auto wrap = node.find("wrap")) {
      const std::string v = wrap->string();
      if (v == "repeat")
        t.wrap = TextureWrap::repeat;
      else if (v == "clamp")
        t.wrap = TextureWrap::clamp;
      else if (v == "black")
        t.wrap = TextureWrap::black;
      else
        wrap->fail("unknown wrap \"" + v + "\" (repeat, clamp, black)");
    }
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
