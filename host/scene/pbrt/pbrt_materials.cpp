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
  const PbrtTexture& t = pbrt_texture_named(*p, textures.spectrum, "spectrum");
  if (t.kasha_name.empty()) {
    material["passive"]["reflectance"] =
        pbrt_texture_constant(t, PbrtSpectrumUse::kAlbedo, base_dir);
    return;
  }
  // A factor above 1 was made a scale texture where the texture was defined (pbrt_textures.cpp).
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
    const PbrtTexture& t = pbrt_texture_named(*p, textures.spectrum, "spectrum");
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

// One roughness parameter: its number, or a float texture that varies over the surface as
// {"texture": NAME} (kasha evaluates it per point; a coat, whose tables take one roughness, its
// mean).
std::optional<nlohmann::json> roughness_param(const PbrtParameters& params, const std::string& name,
                                              PbrtTextures& textures) {
  const PbrtParameter* p = params.find(name, "float texture");
  if (p && p->type == "texture") {
    const PbrtTexture& t = pbrt_texture_named(*p, textures.scalar, "float");
    // A coat's texture too: kasha reads it as its mean, with a warning (scene.cpp).
    if (!t.kasha_name.empty()) return nlohmann::json{{"texture", pbrt_kasha_texture(t, textures)}};
  }
  const std::optional<double> v = pbrt_float_value(params, name, textures);
  if (!v) return std::nullopt;
  return nlohmann::json(*v);
}

// Roughness as pbrt-v4 names it (after `prefix`: coatedconductor's "interface." and
// "conductor."), into kasha's keys (the same names).
void roughness(const PbrtParameters& params, PbrtTextures& textures, nlohmann::json& out,
               const std::string& prefix = "") {
  const auto r = roughness_param(params, prefix + "roughness", textures);
  const auto u = roughness_param(params, prefix + "uroughness", textures);
  const auto v = roughness_param(params, prefix + "vroughness", textures);
  const nlohmann::json rough = r.value_or(nlohmann::json(0.0));
  const nlohmann::json ur = u.value_or(rough), vr = v.value_or(rough);
  if (ur == vr) {
    if (ur != nlohmann::json(0.0)) out["roughness"] = ur;
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
  const PbrtTexture& t =
      pbrt_texture_named(p, scalar ? textures.scalar : textures.spectrum, "spectrum");
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
  for (const std::string& m : builtin_metal_names())
    if (s == "metal-" + m + "-" + suffix) return m;
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
                         PbrtTextures& textures, const std::filesystem::path& base_dir,
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
        !pbrt_texture_named(*r, textures.spectrum, "spectrum").kasha_name.empty())
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
                          const PbrtLocation& where, PbrtTextures& textures,
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
  for (const char* key : {"roughness", "uroughness", "vroughness"}) {
    if (!r.contains(key)) continue;
    if (r[key].is_object()) return true;  // a texture: kasha takes it as rough
    if ((remap ? std::sqrt(r[key].get<double>()) : r[key].get<double>()) >= 1e-3) return true;
  }
  return false;
}

// pbrt-v4's CoatedConductorMaterial: a conductor ("conductor.eta"/"conductor.k" or
// "reflectance", copper by default) under a dielectric coat ("interface.eta" 1.5, "thickness").
// Both smooth sum in closed form (docs/materials.md#coated-conductors); either rough is kasha's
// rough layered metal (docs/materials.md#rough-coated-conductors), whose metal takes one
// roughness (a conductor.roughness texture is refused).
void coated_conductor(const PbrtParameters& params, const PbrtLocation& where,
                      PbrtTextures& textures, const std::filesystem::path& base_dir,
                      nlohmann::json& m) {
  m["conductor"] = conductor(params, where, textures, base_dir, "conductor.");
  m["coat"] = coat_layer("coatedconductor", params, where, textures, base_dir, "interface.eta",
                         "interface.");
  for (const char* key : {"roughness", "uroughness", "vroughness"})
    if (m["conductor"].contains(key) && m["conductor"][key].is_object())
      pbrt_fail(where,
                "coatedconductor: a textured conductor.roughness is not built in kasha (the "
                "layer under the coat takes one roughness)");
  if (!rough(m["conductor"])) m["conductor"].erase("remap_roughness");
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
    const PbrtTexture& t = pbrt_texture_named(*amount, textures.scalar, "float");
    if (!t.kasha_name.empty()) {  // a float texture's factor is in it (pbrt_textures.cpp)
      out["amount"] = t.kasha_name;
      return out;
    }
  }
  out["amount"] = std::clamp(pbrt_float_value(params, "amount", textures).value_or(0.5), 0.0, 1.0);
  return out;
}

// pbrt-v4's "string normalmap": the file, relative to the scene's folder as pbrt-v4 resolves it
// and as the scene's JSON resolves it. pbrt-v4's mix takes none (the material it picks shades).
void normal_map(const std::string& type, const PbrtParameters& params, nlohmann::json& m) {
  const PbrtParameter* n = params.find("normalmap", "string");
  if (!n) return;
  const std::string file = params.get_string("normalmap", "");
  if (type == "mix")
    pbrt_warn(n->where, "pbrt-v4 ignores a mix's normal map (its materials' own apply)");
  else if (!file.empty())
    m["normal_map"] = file;
}

}  // namespace

nlohmann::json pbrt_material(const std::string& type, const PbrtParameters& params,
                             const PbrtLocation& where, PbrtTextures& textures,
                             const std::filesystem::path& base_dir) {
  if (type == "interface" || type == "none" || type.empty()) return nullptr;
  nlohmann::json m = nlohmann::json::object();
  if (const PbrtParameter* d = params.find("displacement", "float texture"))
    pbrt_warn(d->where, "displacement is not built in kasha: the surface is rendered flat");
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
  normal_map(type, params, m);
  params.warn_unused("Material " + in_quotes(type));
  return m;
}

}  // namespace kasha
