#include "scene/texture.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "core/printable.h"
#include "scene/transform.h"
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
  const std::filesystem::path file = f.file_path();
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

bool Texture::program() const {
  if (type != TextureType::image && type != TextureType::checkerboard) return true;
  if (mapping != TextureMapping::uv || dimension != 2) return true;
  for (const auto& [key, in] : inputs)
    if (!in.texture_name.empty()) return true;
  return false;
}

namespace {

// An operand: {"texture": NAME}, a number or a spectrum value.
TextureInput parse_input(const JsonNode& n) {
  TextureInput in;
  in.where = n.where();
  if (n.is_object() && n.has("texture")) {
    in.texture_name = n.at("texture").string();
    n.finish();
    return in;
  }
  if (n.is_number()) {
    in.is_number = true;
    in.number = n.number_in(-1e6, 1e6);
  }
  in.spectrum = parse_spectrum(n);
  return in;
}

// The operands a type takes (pbrt-v4's names) and their defaults (pbrt-v4's).
void parse_inputs(const JsonNode& node, Texture& t,
                  std::initializer_list<std::pair<const char*, double>> names) {
  for (const auto& [key, fallback] : names) {
    if (auto n = node.find(key)) {
      t.inputs[key] = parse_input(*n);
    } else {
      TextureInput in;
      in.is_number = true;
      in.number = fallback;
      in.spectrum = std::make_shared<ConstantSpectrum>(fallback);
      in.where = node.where();
      t.inputs[key] = in;
    }
  }
}

// "mapping" (uv, spherical, cylindrical, planar, with "v1", "v2") and "transform", the
// texture's space in the world (spherical, cylindrical, planar and 3D textures).
void parse_mapping(const JsonNode& node, Texture& t, bool solid) {
  if (auto m = node.find("mapping")) {
    if (solid) m->fail("a 3D texture maps the point itself (no \"mapping\")");
    const std::string v = m->string();
    if (v == "uv")
      t.mapping = TextureMapping::uv;
    else if (v == "spherical")
      t.mapping = TextureMapping::spherical;
    else if (v == "cylindrical")
      t.mapping = TextureMapping::cylindrical;
    else if (v == "planar")
      t.mapping = TextureMapping::planar;
    else
      m->fail("unknown mapping \"" + printable(v) + "\" (uv, spherical, cylindrical, planar)");
  }
  auto vec = [&](const char* key, Eigen::Vector3d& out) {
    if (auto n = node.find(key)) {
      if (t.mapping != TextureMapping::planar) n->fail("only a planar mapping takes it");
      const auto a = n->vec3();
      out = {a[0], a[1], a[2]};
    }
  };
  vec("v1", t.v1);
  vec("v2", t.v2);
  if (auto tr = node.find("transform")) {
    if (!solid && t.mapping == TextureMapping::uv)
      tr->fail("a (u, v) mapping takes no \"transform\"");
    t.texture_from_world = parse_transform(*tr).inverse();
  }
}

// A noise texture's octaves and roughness (pbrt-v4's ω).
void parse_noise(const JsonNode& node, Texture& t) {
  if (auto n = node.find("octaves")) t.octaves = n->integer_in(0, 32);
  if (auto n = node.find("roughness")) t.roughness = n->number_in(-1e3, 1e3);
}

// The type's own keys.
void parse_type(const JsonNode& node, const std::string& type, Texture& t) {
  bool solid = false;
  if (type == "image") {
    parse_image_texture(node, t);
  } else if (type == "checkerboard") {
    t.type = TextureType::checkerboard;
    if (auto d = node.find("dimension")) {
      t.dimension = d->integer_in(2, 3);
      solid = t.dimension == 3;
    }
    JsonNode even = node.at("even"), odd = node.at("odd");
    t.inputs["even"] = parse_input(even);
    t.inputs["odd"] = parse_input(odd);
    // Squares of values keep them as before: (u, v) checkerboards of values skip the programs.
    t.even = t.inputs["even"].spectrum;
    t.odd = t.inputs["odd"].spectrum;
    if (t.inputs["even"].is_number) t.even_value = t.inputs["even"].number;
    if (t.inputs["odd"].is_number) t.odd_value = t.inputs["odd"].number;
  } else if (type == "constant") {
    t.type = TextureType::constant;
    t.inputs["value"] = parse_input(node.at("value"));
  } else if (type == "scale") {
    t.type = TextureType::scale;
    parse_inputs(node, t, {{"tex", 1}, {"scale", 1}});
  } else if (type == "mix") {
    t.type = TextureType::mix;
    parse_inputs(node, t, {{"tex1", 0}, {"tex2", 1}, {"amount", 0.5}});
  } else if (type == "directionmix") {
    t.type = TextureType::directionmix;
    solid = true;  // no mapping; its "transform" turns "dir"
    parse_inputs(node, t, {{"tex1", 0}, {"tex2", 1}});
    if (auto d = node.find("dir")) {
      const auto a = d->vec3();
      t.dir = {a[0], a[1], a[2]};
      if (t.dir.norm() == 0) d->fail("a direction of length 0");
    }
  } else if (type == "bilerp") {
    t.type = TextureType::bilerp;
    parse_inputs(node, t, {{"v00", 0}, {"v01", 1}, {"v10", 0}, {"v11", 1}});
    for (const char* k : {"v00", "v01", "v10", "v11"})
      if (!t.inputs[k].texture_name.empty())
        node.at(k).fail("a bilerp's corners are values, not textures (as pbrt-v4's)");
  } else if (type == "dots") {
    t.type = TextureType::dots;
    parse_inputs(node, t, {{"inside", 1}, {"outside", 0}});
  } else if (type == "fbm" || type == "wrinkled" || type == "marble") {
    t.type = type == "fbm"        ? TextureType::fbm
             : type == "wrinkled" ? TextureType::wrinkled
                                  : TextureType::marble;
    solid = true;
    parse_noise(node, t);
    if (t.type == TextureType::marble) {
      if (auto n = node.find("scale")) t.marble_scale = n->number_in(-1e6, 1e6);
      if (auto n = node.find("variation")) t.variation = n->number_in(-1e6, 1e6);
    }
  } else if (type == "windy") {
    t.type = TextureType::windy;
    solid = true;
  } else {
    node.at("type").fail("unknown texture type \"" + printable(type) +
                         "\" (image, checkerboard, constant, scale, mix, directionmix, bilerp, "
                         "dots, fbm, wrinkled, windy, marble)");
  }
  parse_mapping(node, t, solid);
  // directionmix's "dir" is in the texture's space, as pbrt-v4 reads it.
  if (t.type == TextureType::directionmix)
    t.dir = (t.texture_from_world.inverse().linear() * t.dir).normalized();
}

}  // namespace

Texture parse_texture(const JsonNode& node, const std::string& name) {
  if (!node.is_object()) node.fail("expected a texture object");
  Texture t;
  t.name = name;
  t.where = node.where();
  parse_type(node, node.at("type").string(), t);
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

namespace {

// Fails where a texture names itself in turn.
void check_cycles(const std::vector<Texture>& textures, int at, std::vector<int>& state) {
  state[at] = 1;  // on the current chain
  for (const auto& [key, in] : textures[at].inputs) {
    if (in.texture < 0) continue;
    if (state[in.texture] == 1)
      throw Error(in.where + ": the texture \"" + printable(textures[at].name) +
                  "\" names itself in turn");
    if (state[in.texture] == 0) check_cycles(textures, in.texture, state);
  }
  state[at] = 2;
}

}  // namespace

void resolve_texture_inputs(std::vector<Texture>& textures) {
  for (Texture& t : textures)
    for (auto& [key, in] : t.inputs) {
      if (in.texture_name.empty()) continue;
      for (size_t i = 0; i < textures.size(); ++i)
        if (textures[i].name == in.texture_name) in.texture = static_cast<int>(i);
      if (in.texture < 0)
        throw Error(in.where + ": no texture named \"" + printable(in.texture_name) +
                    "\" in the scene's \"textures\"");
    }
  std::vector<int> state(textures.size(), 0);
  for (size_t i = 0; i < textures.size(); ++i)
    if (state[i] == 0) check_cycles(textures, static_cast<int>(i), state);
}

}  // namespace kasha
