#include "scene/pbrt/pbrt_textures.h"

#include <Eigen/LU>
#include <cctype>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "image/color_encoding.h"

namespace kasha {

const PbrtTexture& pbrt_texture_named(const PbrtParameter& p,
                                      const std::map<std::string, PbrtTexture>& in,
                                      const char* kind) {
  if (p.strings.size() != 1) pbrt_fail(p.where, in_quotes(p.declaration()) + " names one texture");
  auto t = in.find(p.strings[0]);
  if (t == in.end())
    pbrt_fail(p.where, in_quotes(p.declaration()) + ": no " + kind + " texture named " +
                           in_quotes(p.strings[0]) + " was defined before");
  return t->second;
}

namespace {

// v times f: a number multiplied, a spectrum object given a "scale".
nlohmann::json scaled(nlohmann::json v, double f, const PbrtLocation& where) {
  if (f == 1) return v;
  if (v.is_number()) return v.get<double>() * f;
  if (!v.is_object())
    pbrt_fail(where, "a named spectrum scaled by a \"scale\" texture is not built in kasha");
  v["scale"] = v.value("scale", 1.0) * f;
  return v;
}

// The texture's transform as kasha's JSON "transform" (world from texture); a singular one is
// refused, as pbrt-v4 cannot invert it.
nlohmann::json texture_transform(const Eigen::Matrix4d& m, const PbrtLocation& where) {
  if (!(std::abs(m.topLeftCorner<3, 3>().determinant()) > 1e-300) || !m.allFinite() ||
      m.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
    pbrt_fail(where, "the texture's transform is singular or projective");
  std::vector<double> v;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) v.push_back(m(r, c));
  return {{"matrix", v}};
}

// pbrt-v4's TextureMapping2D::Create: "mapping" uv (uscale, vscale, udelta, vdelta), spherical,
// cylindrical or planar (v1, v2, udelta, vdelta), the last three in the texture's space.
void mapping_2d(const PbrtParameters& params, const PbrtLocation& where,
                const Eigen::Matrix4d& world_from_texture, nlohmann::json& out) {
  const std::string mapping = params.get_string("mapping", "uv");
  if (mapping == "uv") {
    out["uscale"] = params.get_float("uscale", 1);
    out["vscale"] = params.get_float("vscale", 1);
    if (out["uscale"] == 0 || out["vscale"] == 0) pbrt_fail(where, "a texture scale of 0");
  } else if (mapping == "spherical" || mapping == "cylindrical" || mapping == "planar") {
    out["mapping"] = mapping;
    out["transform"] = texture_transform(world_from_texture, where);
    if (mapping == "planar") {
      const auto v1 = params.get_triple("v1"), v2 = params.get_triple("v2");
      out["v1"] = v1 ? *v1 : std::array<double, 3>{1, 0, 0};
      out["v2"] = v2 ? *v2 : std::array<double, 3>{0, 1, 0};
    }
  } else {
    pbrt_fail(where, "unknown texture mapping " + in_quotes(mapping) +
                         " (uv, spherical, cylindrical, planar)");
  }
  if (mapping == "uv" || mapping == "planar") {
    out["udelta"] = params.get_float("udelta", 0);
    out["vdelta"] = params.get_float("vdelta", 0);
  }
}

// An operand of a texture of textures (`kind` "spectrum" or "float"): a value as kasha's JSON,
// or {"texture": NAME}; pbrt-v4's default when absent.
nlohmann::json operand(const PbrtParameters& params, const std::string& name,
                       const std::string& kind, double fallback, PbrtTextures& textures,
                       const std::filesystem::path& base_dir) {
  const bool scalar = kind == "float";
  const PbrtParameter* p =
      params.find(name, scalar ? "float texture" : "float rgb spectrum blackbody texture");
  if (!p) return fallback;
  if (p->type != "texture") {
    if (scalar) {
      if (p->numbers.size() != 1)
        pbrt_fail(p->where, in_quotes(p->declaration()) + " takes one value");
      return p->numbers[0];
    }
    return pbrt_spectrum(*p, PbrtSpectrumUse::kAlbedo, base_dir);
  }
  const PbrtTexture& t =
      pbrt_texture_named(*p, scalar ? textures.scalar : textures.spectrum, kind.c_str());
  const std::string kasha = pbrt_kasha_texture(t, textures);
  if (!kasha.empty()) return {{"texture", kasha}};
  if (!scalar) return pbrt_texture_constant(t, PbrtSpectrumUse::kAlbedo, base_dir);
  return t.value ? t.value->numbers.at(0) * t.factor : t.factor;
}

// pbrt-v4's noise textures' parameters (fbm, wrinkled, marble).
void noise_parameters(const PbrtParameters& params, nlohmann::json& out) {
  const int octaves = params.get_int("octaves", 8);
  out["octaves"] = std::clamp(octaves, 0, 32);
  out["roughness"] = params.get_float("roughness", 0.5);
}

// A texture class whose operands are textures (checkerboard, scale, mix, directionmix, dots,
// bilerp) or which varies by itself (fbm, wrinkled, windy, marble); null for another class.
nlohmann::json texture_of_textures(const std::string& kind, const std::string& cls,
                                   const PbrtParameters& params, const PbrtLocation& where,
                                   const Eigen::Matrix4d& world_from_texture,
                                   PbrtTextures& textures, const std::filesystem::path& base_dir) {
  auto in = [&](const char* name, double fallback) {
    return operand(params, name, kind, fallback, textures, base_dir);
  };
  nlohmann::json t = {{"type", cls}};
  if (cls == "checkerboard") {
    const int dimension = params.get_int("dimension", 2);
    if (dimension != 2 && dimension != 3)
      pbrt_fail(where, "a checkerboard's \"dimension\" is 2 or 3");
    t["even"] = in("tex1", 1);
    t["odd"] = in("tex2", 0);
    if (dimension == 3) {
      t["dimension"] = 3;
      t["transform"] = texture_transform(world_from_texture, where);
    } else {
      mapping_2d(params, where, world_from_texture, t);
    }
  } else if (cls == "mix" || cls == "directionmix") {
    t["tex1"] = in("tex1", 0);
    t["tex2"] = in("tex2", 1);
    if (cls == "mix") {
      t["amount"] = operand(params, "amount", "float", 0.5, textures, base_dir);
    } else {
      const auto dir = params.get_triple("dir");
      t["dir"] = dir ? *dir : std::array<double, 3>{0, 1, 0};
      t["transform"] = texture_transform(world_from_texture, where);
    }
  } else if (cls == "scale") {
    t["tex"] = in("tex", 1);
    t["scale"] = operand(params, "scale", "float", 1, textures, base_dir);
  } else if (cls == "dots") {
    // pbrt-v4's DotsTexture::Create hands "inside" to the constructor's outsideDot and "outside"
    // to insideDot: its "inside" colours the background. pbrt-v4's image is the specification.
    t["inside"] = in("outside", 0);
    t["outside"] = in("inside", 1);
    mapping_2d(params, where, world_from_texture, t);
  } else if (cls == "bilerp") {
    for (const char* v : {"v00", "v01", "v10", "v11"}) {
      const nlohmann::json value = in(v, v[2] == '1' ? 1 : 0);
      if (value.is_object() && value.contains("texture"))
        pbrt_fail(where, "a bilerp's corners are values, not textures");
      t[v] = value;
    }
    mapping_2d(params, where, world_from_texture, t);
  } else if (cls == "fbm" || cls == "wrinkled" || cls == "windy" || cls == "marble") {
    if ((cls == "marble") != (kind == "spectrum"))
      pbrt_fail(where, "a " + in_quotes(cls) + " texture is of type " +
                           in_quotes(cls == "marble" ? "spectrum" : "float") + " in pbrt-v4");
    if (cls != "windy") noise_parameters(params, t);
    if (cls == "marble") {
      t["scale"] = params.get_float("scale", 1);
      t["variation"] = params.get_float("variation", 0.2);
    }
    t["transform"] = texture_transform(world_from_texture, where);
  } else {
    return nullptr;
  }
  return t;
}

// Whether a pbrt "scale" texture folds into a factor: its "scale" is a constant and its "tex" a
// constant or one kasha texture.
bool scale_folds(const PbrtParameters& params, const PbrtTextures& textures) {
  const PbrtParameter* s = params.find("scale", "float texture");
  return !s || s->type != "texture" ||
         pbrt_texture_named(*s, textures.scalar, "float").kasha_name.empty();
}

// pbrt-v4's imagemap (textures.cpp): its filter (point, bilinear; trilinear and EWA, which
// filter by the footprint, approximated by bilinear), wrap, scale, invert and encoding (which
// pbrt-v4 applies to PNGs only: other 8-bit formats are sRGB, float formats linear).
nlohmann::json imagemap(const std::string& name, const PbrtParameters& params,
                        const PbrtLocation& where, const Eigen::Matrix4d& world_from_texture,
                        PbrtTextures& textures, PbrtTexture& t) {
  nlohmann::json image = {{"type", "image"}};
  const std::string file = params.get_string("filename", "");
  if (file.empty())
    pbrt_fail(where, "imagemap texture " + in_quotes(name) + " has no \"filename\"");
  image["file"] = file;  // relative to the scene's folder, as the scene's JSON resolves it
  const std::string filter = params.get_string("filter", "bilinear");
  image["filter"] = filter == "point" ? "nearest" : "bilinear";
  if (filter != "point" && filter != "bilinear" && filter != "trilinear" && filter != "ewa")
    pbrt_warn(where, "texture " + in_quotes(name) + ": unknown filter " + in_quotes(filter) +
                         ": bilinear, as pbrt-v4 falls back");
  else if ((filter == "trilinear" || filter == "ewa") && !textures.filter_warned) {
    textures.filter_warned = true;
    pbrt_warn(where, "texture " + in_quotes(name) + ": filter " + in_quotes(filter) +
                         " (and every later trilinear or EWA texture) is approximated by "
                         "kasha's bilinear lookup");
  }
  const std::string wrap = params.get_string("wrap", "repeat");
  if (wrap != "repeat" && wrap != "clamp" && wrap != "black" && wrap != "octahedralsphere")
    pbrt_fail(where, "texture " + in_quotes(name) + ": unknown wrap mode " + in_quotes(wrap) +
                         " (repeat, clamp, black, octahedralsphere)");
  image["wrap"] = wrap == "octahedralsphere" ? "octahedral_sphere" : wrap;
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string encoding = params.get_string("encoding", ext == ".png" ? "sRGB" : "linear");
  try {
    parse_color_encoding(encoding);
  } catch (const Error& e) {
    pbrt_fail(where, "texture " + in_quotes(name) + ": " + e.what());
  }
  if (ext == ".png") image["encoding"] = encoding;
  params.get_float("maxanisotropy", 8);  // a filter setting: kasha does not filter by footprint
  mapping_2d(params, where, world_from_texture, image);
  // pbrt-v4 inverts the scaled value; without inversion the scale is the texture's factor.
  const double scale = params.get_float("scale", 1);
  if (params.get_bool("invert", false)) {
    image["invert"] = true;
    image["scale"] = scale;
  } else {
    t.factor = scale;
  }
  return image;
}

}  // namespace

void pbrt_define_texture(const std::string& name, const std::string& kind, const std::string& cls,
                         const PbrtParameters& params, const PbrtLocation& where,
                         const Eigen::Matrix4d& world_from_texture, PbrtTextures& textures,
                         const std::filesystem::path& base_dir) {
  if (kind != "spectrum" && kind != "float")
    pbrt_fail(where, "texture " + in_quotes(name) + ": unknown texture type " + in_quotes(kind) +
                         " (\"spectrum\" or \"float\")");
  auto& table = kind == "float" ? textures.scalar : textures.spectrum;
  PbrtTexture t;
  const std::string kasha_name = "pbrt " + kind + " texture " + name;
  auto add = [&](nlohmann::json kasha) {
    textures.kasha[kasha_name] = std::move(kasha);
    t.kasha_name = kasha_name;
  };
  if (cls == "constant") {
    const PbrtParameter* v =
        params.find("value", kind == "float" ? "float" : "float rgb spectrum blackbody");
    // pbrt-v4 makes an albedo version of every spectrum texture: an RGB above 1 is refused here.
    if (v) pbrt_spectrum(*(t.value = *v), PbrtSpectrumUse::kAlbedo, base_dir);
  } else if (cls == "scale" && scale_folds(params, textures)) {
    // tex × a constant: the texture (or constant) with a factor, as kasha applies it.
    const PbrtParameter* tex = params.find(
        "tex", kind == "float" ? "float texture" : "float rgb spectrum blackbody texture");
    const double factor = pbrt_float_value(params, "scale", textures).value_or(1);
    if (tex && tex->type == "texture") {
      t = pbrt_texture_named(*tex, table, kind.c_str());
    } else if (tex) {
      pbrt_spectrum(*(t.value = *tex), PbrtSpectrumUse::kAlbedo, base_dir);
    }
    t.factor *= factor;
  } else if (cls == "imagemap") {
    add(imagemap(name, params, where, world_from_texture, textures, t));
  } else if (cls == "ptex") {
    pbrt_fail(where, "texture " + in_quotes(name) +
                         ": ptex textures are not built in kasha (no Ptex reader)");
  } else {
    nlohmann::json made =
        texture_of_textures(kind, cls, params, where, world_from_texture, textures, base_dir);
    if (made.is_null())
      pbrt_fail(where, "texture " + in_quotes(name) + ": unknown texture class " + in_quotes(cls));
    add(std::move(made));
  }
  if (!t.kasha_name.empty()) textures.added.push_back(t.kasha_name);
  // A factor kasha's uses cannot take as a number becomes a scale texture (a program, clamped
  // where it is a reflectance, as pbrt-v4 clamps): a spectrum's above 1, any on a number's.
  if (!t.kasha_name.empty() && (kind == "float" ? t.factor != 1 : t.factor > 1)) {
    t.kasha_name = pbrt_kasha_texture(t, textures);
    t.factor = 1;
  }
  params.warn_unused("Texture " + in_quotes(name));
  table[name] = t;
}

nlohmann::json pbrt_texture_constant(const PbrtTexture& t, PbrtSpectrumUse use,
                                     const std::filesystem::path& base_dir) {
  const nlohmann::json v = t.value ? pbrt_spectrum(*t.value, use, base_dir) : nlohmann::json(1.0);
  return scaled(v, t.factor, t.value ? t.value->where : PbrtLocation{});
}

std::optional<double> pbrt_float_value(const PbrtParameters& params, const std::string& name,
                                       const PbrtTextures& textures) {
  const PbrtParameter* p = params.find(name, "float texture");
  if (!p) return std::nullopt;
  if (p->type != "texture") {
    if (p->numbers.size() != 1)
      pbrt_fail(p->where, in_quotes(p->declaration()) + " takes one value");
    return p->numbers[0];
  }
  const PbrtTexture& t = pbrt_texture_named(*p, textures.scalar, "float");
  if (!t.kasha_name.empty())
    pbrt_fail(p->where, in_quotes(p->declaration()) + ": a texture that varies over the surface " +
                            "is not built in kasha here (it takes one number)");
  const double factor = t.factor;
  return t.value ? t.value->numbers.at(0) * factor : factor;
}

std::string pbrt_kasha_texture(const PbrtTexture& t, PbrtTextures& textures) {
  if (t.kasha_name.empty() || t.factor == 1) return t.kasha_name;
  std::ostringstream name;
  name << t.kasha_name << " scaled " << t.factor;
  if (!textures.kasha.contains(name.str())) {
    textures.kasha[name.str()] = {
        {"type", "scale"}, {"tex", {{"texture", t.kasha_name}}}, {"scale", t.factor}};
    textures.added.push_back(name.str());
  }
  return name.str();
}

}  // namespace kasha
