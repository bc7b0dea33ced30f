#include "scene/pbrt/pbrt_materials.h"

#include "core/printable.h"
#include "scene/pbrt/pbrt_spectra.h"

namespace kasha {

namespace {

const PbrtTexture& texture_named(const PbrtParameter& p, const std::map<std::string, PbrtTexture>& in,
                                 const char* kind) {
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
  const PbrtParameter* p = params.find(name, kind == "float" ? "float texture"
                                                             : "float rgb spectrum texture");
  if (!p) return fallback;
  if (p->type == "texture") {
    const PbrtTexture& t =
        texture_named(*p, kind == "float" ? textures.scalar : textures.spectrum, kind.c_str());
    if (!t.kasha_name.empty())
      pbrt_fail(p->where, in_quotes(p->declaration()) +
                              ": a checkerboard of textures is not built in kasha (its squares "
                              "take values)");
    return t.constant;
  }
  return pbrt_spectrum(*p, PbrtSpectrumUse::kAlbedo, base_dir);
}

// The (s, t) mapping parameters shared by pbrt's 2D textures.
void uv_mapping(const PbrtParameters& params, const PbrtLocation& where, nlohmann::json& out) {
  const std::string mapping = params.get_string("mapping", "uv");
  if (mapping != "uv")
    pbrt_fail(where, "texture mapping " + in_quotes(mapping) +
                         " is not built in kasha (only \"uv\")");
  out["uscale"] = params.get_float("uscale", 1);
  out["vscale"] = params.get_float("vscale", 1);
  out["udelta"] = params.get_float("udelta", 0);
  out["vdelta"] = params.get_float("vdelta", 0);
  if (out["uscale"] == 0 || out["vscale"] == 0) pbrt_fail(where, "a texture scale of 0");
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
    const PbrtParameter* v = params.find("value", kind == "float" ? "float" : "float rgb spectrum");
    t.constant = v ? pbrt_spectrum(*v, PbrtSpectrumUse::kAlbedo, base_dir) : nlohmann::json(1.0);
  } else if (cls == "scale") {
    // tex × scale, each a value or a texture; kasha keeps at most one texture times a number.
    const PbrtParameter* tex = params.find("tex", kind == "float" ? "float texture"
                                                                  : "float rgb spectrum texture");
    const PbrtParameter* scale = params.find("scale", "float texture");
    double factor = 1;
    if (scale && scale->type == "texture") {
      const PbrtTexture& s = texture_named(*scale, textures.scalar, "float");
      if (!s.kasha_name.empty() || !s.constant.is_number())
        pbrt_fail(scale->where, "a \"scale\" texture's \"scale\" must be a number in kasha");
      factor = s.constant.get<double>();
    } else if (scale) {
      factor = scale->numbers[0];
    }
    if (tex && tex->type == "texture") {
      t = texture_named(*tex, table, kind.c_str());
      if (!t.kasha_name.empty())
        t.factor *= factor;
      else if (t.constant.is_number())
        t.constant = t.constant.get<double>() * factor;
      else
        t.constant["scale"] = t.constant.value("scale", 1.0) * factor;
    } else {
      nlohmann::json v = tex ? pbrt_spectrum(*tex, PbrtSpectrumUse::kAlbedo, base_dir)
                             : nlohmann::json(1.0);
      if (v.is_number())
        v = v.get<double>() * factor;
      else
        v["scale"] = factor;
      t.constant = v;
    }
  } else if (cls == "imagemap") {
    nlohmann::json image = {{"type", "image"}};
    const std::string file = params.get_string("filename", "");
    if (file.empty()) pbrt_fail(where, "imagemap texture " + in_quotes(name) + " has no \"filename\"");
    const std::filesystem::path path(file);
    image["file"] = file;  // relative to the scene's folder, as the scene's JSON resolves it
    const std::string filter = params.get_string("filter", "bilinear");
    if (filter == "point") {
      image["filter"] = "nearest";
    } else {
      image["filter"] = "bilinear";
      if (filter != "bilinear")
        pbrt_warn(where, "texture " + in_quotes(name) + ": filter " + in_quotes(filter) +
                             " is approximated by kasha's bilinear lookup");
    }
    const std::string wrap = params.get_string("wrap", "repeat");
    if (wrap != "repeat" && wrap != "clamp" && wrap != "black")
      pbrt_fail(where, "texture " + in_quotes(name) + ": wrap mode " + in_quotes(wrap) +
                           " is not built in kasha (repeat, clamp, black)");
    image["wrap"] = wrap;
    if (params.get_bool("invert", false))
      pbrt_fail(where, "texture " + in_quotes(name) + ": \"invert\" is not built in kasha");
    const std::string encoding = params.get_string("encoding", "");
    const std::string ext = path.extension().string();
    if (!encoding.empty()) {
      const bool exr = ext == ".exr" || ext == ".EXR";
      const bool as_kasha = exr ? encoding == "linear" : encoding == "sRGB";
      if (!as_kasha)
        pbrt_fail(where, "texture " + in_quotes(name) + ": encoding " + in_quotes(encoding) +
                             " is not kasha's for this file (PNG is read as sRGB, EXR as linear)");
    }
    params.get_float("maxanisotropy", 8);  // a filter setting: kasha does not filter by footprint
    uv_mapping(params, where, image);
    t.kasha_name = kasha_name;
    t.factor = params.get_float("scale", 1);
    textures.kasha[kasha_name] = image;
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
  const PbrtParameter* p = params.find("reflectance", "float rgb spectrum texture");
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
    material["passive"]["reflectance"] = t.constant;
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
    if (t.kasha_name.empty()) return t.constant;
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

// Roughness as pbrt-v4 names it, into kasha's keys (the same names).
void roughness(const PbrtParameters& params, nlohmann::json& out) {
  const PbrtParameter* r = params.find("roughness", "float texture");
  const PbrtParameter* u = params.find("uroughness", "float texture");
  const PbrtParameter* v = params.find("vroughness", "float texture");
  for (const PbrtParameter* p : {r, u, v})
    if (p && p->type == "texture")
      pbrt_fail(p->where, in_quotes(p->declaration()) + ": a roughness texture is not built in kasha");
  const double rough = r ? r->numbers[0] : 0;
  const double ur = u ? u->numbers[0] : rough, vr = v ? v->numbers[0] : rough;
  if (ur == vr) {
    if (ur != 0) out["roughness"] = ur;
  } else {
    out["uroughness"] = ur;
    out["vroughness"] = vr;
  }
  out["remap_roughness"] = params.get_bool("remaproughness", true);
}

nlohmann::json index_of_refraction(const PbrtParameters& params, const std::filesystem::path& base_dir) {
  const PbrtParameter* eta = params.find("eta", "float spectrum texture");
  if (!eta) return 1.5;
  if (eta->type == "texture")
    pbrt_fail(eta->where, in_quotes(eta->declaration()) + ": an index texture is not built in kasha");
  return pbrt_spectrum(*eta, PbrtSpectrumUse::kUnbounded, base_dir);
}

// "metal-Au-eta" → "Au" for kasha's built-in tables; empty otherwise.
std::string metal_of(const PbrtParameter* p, const char* suffix) {
  if (!p || p->type != "spectrum" || p->strings.size() != 1) return "";
  const std::string& s = p->strings[0];
  for (const char* m : {"Ag", "Al", "Au", "Cu"})
    if (s == std::string("metal-") + m + "-" + suffix) return m;
  return "";
}

}  // namespace

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
    nlohmann::json coat = nlohmann::json::object();
    const nlohmann::json eta = index_of_refraction(params, base_dir);
    if (!eta.is_number())
      pbrt_fail(where, "coateddiffuse: a coat's index must be a number in kasha");
    coat["eta"] = eta;
    coat["thickness"] = params.get_float("thickness", 0.01);
    roughness(params, coat);
    const PbrtParameter* albedo = params.find("albedo", "float rgb spectrum texture");
    if (albedo && !(albedo->type == "float" && albedo->numbers[0] == 0))
      pbrt_fail(albedo->where, "coateddiffuse: a scattering coat (\"albedo\" > 0) is not built "
                               "in kasha");
    // Settings of pbrt-v4's stochastic evaluation, which kasha's closed form does not need
    // (docs/materials.md#coated-surfaces: kasha sums every round trip).
    params.get_int("maxdepth", 10);
    params.get_int("nsamples", 1);
    params.get_float("g", 0);
    m["coat"] = coat;
  } else if (type == "dielectric") {
    nlohmann::json d = {{"eta", index_of_refraction(params, base_dir)}};
    roughness(params, d);
    m["dielectric"] = d;
  } else if (type == "conductor") {
    nlohmann::json c = nlohmann::json::object();
    if (const PbrtParameter* r = params.find("reflectance", "float rgb spectrum texture"))
      pbrt_fail(r->where, "conductor: \"reflectance\" (an artist's metal) is not built in kasha: "
                          "give \"eta\" and \"k\"");
    const PbrtParameter* eta = params.find("eta", "float spectrum texture");
    const PbrtParameter* k = params.find("k", "float spectrum texture");
    for (const PbrtParameter* p : {eta, k})
      if (p && p->type == "texture")
        pbrt_fail(p->where, in_quotes(p->declaration()) + ": a texture is not built in kasha here");
    const std::string me = metal_of(eta, "eta"), mk = metal_of(k, "k");
    if (!eta && !k) {
      c["metal"] = "Cu";  // pbrt-v4's default
    } else if (!me.empty() && me == mk) {
      c["metal"] = me;
    } else {
      if (!eta || !k) pbrt_fail(where, "conductor: give both \"eta\" and \"k\"");
      c["eta"] = pbrt_spectrum(*eta, PbrtSpectrumUse::kUnbounded, base_dir);
      c["k"] = pbrt_spectrum(*k, PbrtSpectrumUse::kUnbounded, base_dir);
    }
    roughness(params, c);
    m["conductor"] = c;
  } else if (type == "thindielectric") {
    // pbrt-v4's ThinDielectricMaterial: "eta" (1.5), smooth.
    const nlohmann::json eta = index_of_refraction(params, base_dir);
    if (!eta.is_number()) pbrt_fail(where, "thindielectric: \"eta\" must be a number in kasha");
    m["dielectric"] = {{"eta", eta}, {"thin", true}};
  } else if (type == "diffusetransmission") {
    diffuse_transmission(params, textures, base_dir, m);
  } else if (type == "kasha") {
    // A material file kasha measured or wrote (docs/pbrt-import.md#measured-materials-in-pbrt-scenes).
    const std::string file = params.get_string("file", "");
    if (file.empty()) pbrt_fail(where, "Material \"kasha\" needs \"string file\"");
    m["file"] = file;
  } else if (type == "mix" || type == "measured" || type == "hair" || type == "subsurface" ||
             type == "coatedconductor") {
    pbrt_fail(where, "material " + in_quotes(type) + " is not built in kasha (diffuse, "
                     "coateddiffuse, diffusetransmission, dielectric, thindielectric, conductor, kasha)");
  } else {
    pbrt_fail(where, "unknown material type " + in_quotes(type));
  }
  params.warn_unused("Material " + in_quotes(type));
  return m;
}

}  // namespace kasha
