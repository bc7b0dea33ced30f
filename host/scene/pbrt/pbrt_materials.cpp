#include "scene/pbrt/pbrt_materials.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.h"
#include "core/printable.h"
#include "image/color_encoding.h"
#include "material/metals.h"
#include "scene/pbrt/pbrt_spectra.h"

namespace kasha {

namespace {

const PbrtTexture& texture_named(const PbrtParameter& p,
                                 const std::map<std::string, PbrtTexture>& in, const char* kind) {
  if (p.strings.size() != 1) pbrt_fail(p.where, in_quotes(p.declaration()) + " names one texture");
  auto t = in.find(p.strings[0]);
  if (t == in.end())
    pbrt_fail(p.where, in_quotes(p.declaration()) + ": no " + kind + " texture named " +
                           in_quotes(p.strings[0]) + " was defined before");
  return t->second;
}

// A texture's constant value from a spectrum-or-texture parameter given as a value.
nlohmann::json checker_value(const PbrtParameters& params, const char* name, double fallback,
                             const std::string& kind, const PbrtTextures& textures,
                             const std::filesystem::path& base_dir) {
  const PbrtParameter* p =
      params.find(name, kind == "float" ? "float texture" : "float rgb spectrum blackbody texture");
  if (!p) return fallback;
  if (p->type == "texture") {
    const PbrtTexture& t =
        texture_named(*p, kind == "float" ? textures.scalar : textures.spectrum, kind.c_str());
    if (!t.kasha_name.empty())
      pbrt_fail(p->where, in_quotes(p->declaration()) +
                              ": a checkerboard of textures is not built in kasha (its squares "
                              "take values)");
    return pbrt_texture_constant(t, PbrtSpectrumUse::kAlbedo, base_dir);
  }
  return pbrt_spectrum(*p, PbrtSpectrumUse::kAlbedo, base_dir);
}

// v times f: a number multiplied, a spectrum object given a "scale".
nlohmann::json scaled(nlohmann::json v, double f, const PbrtLocation& where) {
  if (f == 1) return v;
  if (v.is_number()) return v.get<double>() * f;
  if (!v.is_object())
    pbrt_fail(where, "a named spectrum scaled by a \"scale\" texture is not built in kasha");
  v["scale"] = v.value("scale", 1.0) * f;
  return v;
}

// The (s, t) mapping parameters shared by pbrt's 2D textures.
void uv_mapping(const PbrtParameters& params, const PbrtLocation& where, nlohmann::json& out) {
  const std::string mapping = params.get_string("mapping", "uv");
  if (mapping != "uv")
    pbrt_fail(where,
              "texture mapping " + in_quotes(mapping) + " is not built in kasha (only \"uv\")");
  out["uscale"] = params.get_float("uscale", 1);
  out["vscale"] = params.get_float("vscale", 1);
  out["udelta"] = params.get_float("udelta", 0);
  out["vdelta"] = params.get_float("vdelta", 0);
  if (out["uscale"] == 0 || out["vscale"] == 0) pbrt_fail(where, "a texture scale of 0");
}

// pbrt-v4's imagemap (textures.cpp): its filter (point, bilinear; trilinear and EWA, which
// filter by the footprint, approximated by bilinear), wrap, scale, invert and encoding (which
// pbrt-v4 applies to PNGs only: other 8-bit formats are sRGB, float formats linear).
nlohmann::json imagemap(const std::string& name, const PbrtParameters& params,
                        const PbrtLocation& where, PbrtTextures& textures, PbrtTexture& t) {
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
  uv_mapping(params, where, image);
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
                         PbrtTextures& textures, const std::filesystem::path& base_dir) {
  if (kind != "spectrum" && kind != "float")
    pbrt_fail(where, "texture " + in_quotes(name) + ": unknown texture type " + in_quotes(kind) +
                         " (\"spectrum\" or \"float\")");
  auto& table = kind == "float" ? textures.scalar : textures.spectrum;
  PbrtTexture t;
  const std::string kasha_name = "pbrt " + kind + " texture " + name;
  if (cls == "constant") {
    const PbrtParameter* v =
        params.find("value", kind == "float" ? "float" : "float rgb spectrum blackbody");
    // pbrt-v4 makes an albedo version of every spectrum texture: an RGB above 1 is refused here.
    if (v) pbrt_spectrum(*(t.value = *v), PbrtSpectrumUse::kAlbedo, base_dir);
  } else if (cls == "scale") {
    // tex × scale, each a value or a texture; kasha keeps at most one texture times a number.
    const PbrtParameter* tex = params.find(
        "tex", kind == "float" ? "float texture" : "float rgb spectrum blackbody texture");
    const double factor = pbrt_float_value(params, "scale", textures).value_or(1);
    if (tex && tex->type == "texture") {
      t = texture_named(*tex, table, kind.c_str());
    } else if (tex) {
      pbrt_spectrum(*(t.value = *tex), PbrtSpectrumUse::kAlbedo, base_dir);
    }
    t.factor *= factor;
  } else if (cls == "imagemap") {
    nlohmann::json image = imagemap(name, params, where, textures, t);
    textures.kasha[kasha_name] = image;
    t.kasha_name = kasha_name;
  } else if (cls == "checkerboard") {
    if (params.get_int("dimension", 2) != 2)
      pbrt_fail(where, "texture " + in_quotes(name) + ": a 3D checkerboard is not built in kasha");
    nlohmann::json checker = {{"type", "checkerboard"}};
    checker["even"] = checker_value(params, "tex1", 1, kind, textures, base_dir);
    checker["odd"] = checker_value(params, "tex2", 0, kind, textures, base_dir);
    uv_mapping(params, where, checker);
    t.kasha_name = kasha_name;
    textures.kasha[kasha_name] = checker;
  } else {
    pbrt_fail(where, "texture " + in_quotes(name) + ": the texture class " + in_quotes(cls) +
                         " is not built in kasha (imagemap, checkerboard, scale, constant)");
  }
  params.warn_unused("Texture " + in_quotes(name));
  table[name] = t;
}

namespace {

// A reflectance given as a value or a spectrum texture: sets material["passive"]["reflectance"]
// and, for a texture, material["textures"]["reflectance"].
void reflectance(const PbrtParameters& params, const PbrtTextures& textures,
                 const std::filesystem::path& base_dir, nlohmann::json& material) {
  const PbrtParameter* p = params.find("reflectance", "float rgb spectrum blackbody texture");
  if (!p) {
    material["passive"]["reflectance"] = 0.5;  // pbrt-v4's default
    return;
  }
  if (p->type != "texture") {
    material["passive"]["reflectance"] = pbrt_spectrum(*p, PbrtSpectrumUse::kAlbedo, base_dir);
    return;
  }
  const PbrtTexture& t = texture_named(*p, textures.spectrum, "spectrum");
  if (t.kasha_name.empty()) {
    material["passive"]["reflectance"] =
        pbrt_texture_constant(t, PbrtSpectrumUse::kAlbedo, base_dir);
    return;
  }
  if (t.factor > 1)
    pbrt_fail(p->where, in_quotes(p->declaration()) + ": a texture scaled by " +
                            std::to_string(t.factor) + " may exceed a reflectance of 1");
  material["passive"]["reflectance"] = t.factor;
  material["textures"]["reflectance"] = t.kasha_name;
}

// pbrt-v4's DiffuseTransmissionMaterial: "reflectance" and "transmittance" (each 0.25 by default, a
// value or a spectrum texture) times "scale", into kasha's passive part and "transmission". A
// texture may colour both only as one texture: kasha's reflectance texture multiplies both.
void diffuse_transmission(const PbrtParameters& params, const PbrtTextures& textures,
                          const std::filesystem::path& base_dir, nlohmann::json& material) {
  std::string texture[2];
  const PbrtParameter* given[2] = {nullptr, nullptr};
  auto part = [&](int k, const char* name) -> nlohmann::json {
    const PbrtParameter* p = given[k] = params.find(name, "float rgb spectrum texture");
    if (!p) return 0.25;  // pbrt-v4's default
    if (p->type != "texture") return pbrt_spectrum(*p, PbrtSpectrumUse::kAlbedo, base_dir);
    const PbrtTexture& t = texture_named(*p, textures.spectrum, "spectrum");
    if (t.kasha_name.empty()) return pbrt_texture_constant(t, PbrtSpectrumUse::kAlbedo, base_dir);
    texture[k] = t.kasha_name;
    return t.factor;
  };
  material["passive"]["reflectance"] = part(0, "reflectance");
  material["transmission"]["transmittance"] = part(1, "transmittance");
  if (texture[0] != texture[1])
    pbrt_fail((given[0] && !texture[0].empty() ? given[0] : given[1])->where,
              "diffusetransmission: a \"reflectance\" and \"transmittance\" not of one texture "
              "is not built in kasha");
  if (!texture[0].empty()) material["textures"]["reflectance"] = texture[0];
  material["transmission"]["scale"] = params.get_float("scale", 1);
}

// Roughness as pbrt-v4 names it (after `prefix`: coatedconductor's "interface." and
// "conductor."), into kasha's keys (the same names).
void roughness(const PbrtParameters& params, const PbrtTextures& textures, nlohmann::json& out,
               const std::string& prefix = "") {
  const std::optional<double> r = pbrt_float_value(params, prefix + "roughness", textures);
  const std::optional<double> u = pbrt_float_value(params, prefix + "uroughness", textures);
  const std::optional<double> v = pbrt_float_value(params, prefix + "vroughness", textures);
  const double rough = r.value_or(0);
  const double ur = u.value_or(rough), vr = v.value_or(rough);
  if (ur == vr) {
    if (ur != 0) out["roughness"] = ur;
  } else {
    out["uroughness"] = ur;
    out["vroughness"] = vr;
  }
  out["remap_roughness"] = params.get_bool("remaproughness", true);
}

// A spectrum parameter or spectrum texture read as `use`; a varying texture is refused (kasha
// takes a spectrum there). A float texture's name is taken too where pbrt-v4 takes a number.
nlohmann::json spectrum_value(const PbrtParameter& p, PbrtSpectrumUse use,
                              const PbrtTextures& textures, const std::filesystem::path& base_dir) {
  if (p.type != "texture") return pbrt_spectrum(p, use, base_dir);
  const bool scalar = p.strings.size() == 1 && textures.scalar.count(p.strings[0]) &&
                      !textures.spectrum.count(p.strings[0]);
  const PbrtTexture& t = texture_named(p, scalar ? textures.scalar : textures.spectrum, "spectrum");
  if (!t.kasha_name.empty())
    pbrt_fail(p.where, in_quotes(p.declaration()) + ": a texture that varies over the surface " +
                           "is not built in kasha here (it takes one spectrum)");
  return pbrt_texture_constant(t, use, base_dir);
}

// Whether a spectrum value the importer made is zero (0, or an RGB or a table of zeros).
bool is_black(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>() == 0;
  if (!v.is_object() || v.value("scale", 1.0) == 0) return v.is_object();
  for (const char* key : {"rgb", "value"})
    if (v.contains(key)) {
      for (const auto& x : v[key])
        if (x.get<double>() != 0) return false;
      return true;
    }
  return false;
}

nlohmann::json index_of_refraction(const PbrtParameters& params, const PbrtTextures& textures,
                                   const std::filesystem::path& base_dir,
                                   const std::string& name = "eta") {
  const PbrtParameter* eta = params.find(name, "float rgb spectrum blackbody texture");
  if (!eta) return 1.5;
  return spectrum_value(*eta, PbrtSpectrumUse::kUnbounded, textures, base_dir);
}

// "metal-Au-eta" → "Au" for kasha's built-in tables; empty otherwise.
std::string metal_of(const PbrtParameter* p, const char* suffix) {
  if (!p || p->type != "spectrum" || p->strings.size() != 1) return "";
  const std::string& s = p->strings[0];
  for (const char* m : {"Ag", "Al", "Au", "Cu"})
    if (s == std::string("metal-") + m + "-" + suffix) return m;
  return "";
}

// pbrt-v4's artist's metal (ConductorMaterial): η = 1 and k = 2√r / √(1 − r), r the reflectance
// clamped to [0, 0.9999], wavelength by wavelength — a metal whose normal reflectance is r.
nlohmann::json artist_k(const nlohmann::json& reflectance, const std::filesystem::path& base_dir,
                        const PbrtLocation& where) {
  const SpectrumPtr r = pbrt_parse_spectrum(reflectance, base_dir, where);
  return pbrt_tabulated([&](double nm) {
    const double v = std::clamp(r->value(nm), 0.0, 0.9999);
    return 2 * std::sqrt(v) / std::sqrt(1 - v);
  });
}

// A conductor's η or k: the parameter's spectrum, a metal-X-eta/-k of kasha's tables (tabulated),
// or copper's when absent (pbrt-v4's default for each alone).
nlohmann::json metal_part(const PbrtParameter* p, const char* part, const PbrtTextures& textures,
                          const std::filesystem::path& base_dir) {
  const std::string metal = p ? metal_of(p, part) : "Cu";
  if (metal.empty()) return spectrum_value(*p, PbrtSpectrumUse::kUnbounded, textures, base_dir);
  const MetalIndex index = builtin_metal(metal);
  const SpectrumPtr& s = std::string(part) == "eta" ? index.eta : index.k;
  return pbrt_tabulated([&](double nm) { return s->value(nm); });
}

// pbrt-v4's ConductorMaterial; `prefix` "conductor." for CoatedConductorMaterial's (whose
// "reflectance" has none).
nlohmann::json conductor(const PbrtParameters& params, const PbrtLocation& where,
                         const PbrtTextures& textures, const std::filesystem::path& base_dir,
                         const std::string& prefix = "") {
  nlohmann::json c = nlohmann::json::object();
  const PbrtParameter* r = params.find("reflectance", "float rgb spectrum blackbody texture");
  const PbrtParameter* eta = params.find(prefix + "eta", "float rgb spectrum blackbody texture");
  const PbrtParameter* k = params.find(prefix + "k", "float rgb spectrum blackbody texture");
  const std::string me = metal_of(eta, "eta"), mk = metal_of(k, "k");
  if (r && (eta || k))
    pbrt_fail(where,
              "conductor: \"reflectance\" and \"eta\"/\"k\" both given (pbrt-v4 "
              "refuses it too)");
  if (r) {
    if (r->type == "texture" &&
        !texture_named(*r, textures.spectrum, "spectrum").kasha_name.empty())
      pbrt_fail(r->where, in_quotes(r->declaration()) + ": a conductor's reflectance texture is " +
                              "not built in kasha (its η and k take one spectrum each)");
    c["eta"] = 1.0;
    c["k"] = artist_k(spectrum_value(*r, PbrtSpectrumUse::kAlbedo, textures, base_dir), base_dir,
                      r->where);
  } else if (!eta && !k) {
    c["metal"] = "Cu";  // pbrt-v4's default
  } else if (!me.empty() && me == mk) {
    c["metal"] = me;
  } else {
    // One of the two alone: pbrt-v4 takes copper's for the other.
    c["eta"] = metal_part(eta, "eta", textures, base_dir);
    c["k"] = metal_part(k, "k", textures, base_dir);
  }
  roughness(params, textures, c, prefix);
  return c;
}

// A coat as pbrt-v4's coateddiffuse and coatedconductor take it: the index `eta_name` (a number
// in kasha), "thickness" (0.01), roughness after `prefix`, and a clear layer: "albedo" 0.
nlohmann::json coat_layer(const std::string& type, const PbrtParameters& params,
                          const PbrtLocation& where, const PbrtTextures& textures,
                          const std::filesystem::path& base_dir, const std::string& eta_name,
                          const std::string& prefix) {
  nlohmann::json coat = nlohmann::json::object();
  const nlohmann::json eta = index_of_refraction(params, textures, base_dir, eta_name);
  if (!eta.is_number()) pbrt_fail(where, type + ": a coat's index must be a number in kasha");
  coat["eta"] = eta;
  coat["thickness"] = pbrt_float_value(params, "thickness", textures).value_or(0.01);
  roughness(params, textures, coat, prefix);
  const PbrtParameter* albedo = params.find("albedo", "float rgb spectrum blackbody texture");
  if (albedo && !is_black(spectrum_value(*albedo, PbrtSpectrumUse::kAlbedo, textures, base_dir)))
    pbrt_fail(albedo->where, type + ": a scattering coat (\"albedo\" > 0) is not built in kasha");
  // Settings of pbrt-v4's stochastic evaluation, which kasha's closed forms do not need
  // (docs/materials.md#coated-surfaces: kasha sums every round trip).
  params.get_int("maxdepth", 10);
  params.get_int("nsamples", 1);
  pbrt_float_value(params, "g", textures);
  return coat;
}

// Whether roughness keys roughness() wrote make a rough surface (alpha ≥ 1e-3, kasha's
// material.h and pbrt-v4's EffectivelySmooth).
bool rough(const nlohmann::json& r) {
  const bool remap = r.value("remap_roughness", true);
  for (const char* key : {"roughness", "uroughness", "vroughness"})
    if (r.contains(key) && (remap ? std::sqrt(r[key].get<double>()) : r[key].get<double>()) >= 1e-3)
      return true;
  return false;
}

// pbrt-v4's CoatedConductorMaterial: a conductor ("conductor.eta"/"conductor.k" or
// "reflectance", copper by default) under a dielectric coat ("interface.eta" 1.5, "thickness").
// kasha builds it with both interfaces smooth (docs/materials.md#coated-conductors).
void coated_conductor(const PbrtParameters& params, const PbrtLocation& where,
                      const PbrtTextures& textures, const std::filesystem::path& base_dir,
                      nlohmann::json& m) {
  m["conductor"] = conductor(params, where, textures, base_dir, "conductor.");
  m["coat"] = coat_layer("coatedconductor", params, where, textures, base_dir, "interface.eta",
                         "interface.");
  if (rough(m["conductor"]) || rough(m["coat"]))
    pbrt_fail(where,
              "coatedconductor: a rough interface or conductor is not built in kasha (both "
              "smooth are: interface.roughness and conductor.roughness 0)");
  m["conductor"].erase("remap_roughness");
}

// pbrt-v4's MixMaterial: "string materials" (two named materials, which the importer checks
// once it knows them) and "float amount" (0.5): a number, clamped to [0, 1] as ChooseMaterial
// reads it, or a float texture that varies over the surface (kasha's scalar texture).
nlohmann::json mix(const PbrtParameters& params, const PbrtLocation& where,
                   const PbrtTextures& textures) {
  const PbrtParameter* names = params.find("materials", "string");
  if (!names || names->strings.size() != 2)
    pbrt_fail(names ? names->where : where, "mix: \"string materials\" must name two materials");
  nlohmann::json out = {{"materials", names->strings}};
  const PbrtParameter* amount = params.find("amount", "float texture");
  if (amount && amount->type == "texture") {
    const PbrtTexture& t = texture_named(*amount, textures.scalar, "float");
    if (!t.kasha_name.empty()) {
      if (t.factor != 1)
        pbrt_fail(amount->where, in_quotes(amount->declaration()) +
                                     ": a scaled texture as a mix's amount is not built in kasha");
      out["amount"] = t.kasha_name;
      return out;
    }
  }
  out["amount"] = std::clamp(pbrt_float_value(params, "amount", textures).value_or(0.5), 0.0, 1.0);
  return out;
}

}  // namespace

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
  const PbrtTexture& t = texture_named(*p, textures.scalar, "float");
  if (!t.kasha_name.empty())
    pbrt_fail(p->where, in_quotes(p->declaration()) + ": a texture that varies over the surface " +
                            "is not built in kasha here (it takes one number)");
  const double factor = t.factor;
  return t.value ? t.value->numbers.at(0) * factor : factor;
}

nlohmann::json pbrt_material(const std::string& type, const PbrtParameters& params,
                             const PbrtLocation& where, const PbrtTextures& textures,
                             const std::filesystem::path& base_dir) {
  if (type == "interface" || type == "none" || type.empty()) return nullptr;
  nlohmann::json m = nlohmann::json::object();
  if (const PbrtParameter* d = params.find("displacement", "float texture"))
    pbrt_warn(d->where, "displacement is not built in kasha: the surface is rendered flat");
  if (const PbrtParameter* n = params.find("normalmap", "string"))
    pbrt_warn(n->where, "normal maps are not built in kasha: the surface is shaded without it");
  if (type == "diffuse") {
    reflectance(params, textures, base_dir, m);
  } else if (type == "coateddiffuse") {
    reflectance(params, textures, base_dir, m);
    m["coat"] = coat_layer(type, params, where, textures, base_dir, "eta", "");
  } else if (type == "coatedconductor") {
    coated_conductor(params, where, textures, base_dir, m);
  } else if (type == "dielectric") {
    nlohmann::json d = {{"eta", index_of_refraction(params, textures, base_dir)}};
    roughness(params, textures, d);
    m["dielectric"] = d;
  } else if (type == "conductor") {
    m["conductor"] = conductor(params, where, textures, base_dir);
  } else if (type == "thindielectric") {
    // pbrt-v4's ThinDielectricMaterial: "eta" (1.5), smooth.
    const nlohmann::json eta = index_of_refraction(params, textures, base_dir);
    if (!eta.is_number()) pbrt_fail(where, "thindielectric: \"eta\" must be a number in kasha");
    m["dielectric"] = {{"eta", eta}, {"thin", true}};
  } else if (type == "diffusetransmission") {
    diffuse_transmission(params, textures, base_dir, m);
  } else if (type == "kasha") {
    // A material file kasha measured or wrote
    // (docs/pbrt-import.md#measured-materials-in-pbrt-scenes).
    const std::string file = params.get_string("file", "");
    if (file.empty()) pbrt_fail(where, "Material \"kasha\" needs \"string file\"");
    m["file"] = file;
  } else if (type == "mix") {
    m["mix"] = mix(params, where, textures);
  } else if (type == "measured" || type == "hair" || type == "subsurface") {
    pbrt_fail(where, "material " + in_quotes(type) +
                         " is not built in kasha (diffuse, coateddiffuse, coatedconductor, "
                         "diffusetransmission, dielectric, thindielectric, conductor, mix, kasha)");
  } else {
    pbrt_fail(where, "unknown material type " + in_quotes(type));
  }
  params.warn_unused("Material " + in_quotes(type));
  return m;
}

}  // namespace kasha
