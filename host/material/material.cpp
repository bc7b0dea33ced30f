#include "material/material.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "material/glasses.h"
#include "material/metals.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

static GlossDesc parse_gloss(const JsonNode& node) {
  GlossDesc g;
  g.reflectance = node.at("reflectance").number_in(0.0, 1.0);
  if (auto mirror = node.find("mirror")) g.mirror = mirror->boolean();
  if (auto cone = node.find("cone_deg")) {
    if (g.mirror) cone->fail("an ideal mirror has no cone");
    g.cone_deg = cone->number_in(1e-3, 90.0);
  }
  if (auto profile = node.find("profile")) {
    if (g.mirror) profile->fail("an ideal mirror has no profile");
    g.profile_deg = profile->at("deg").numbers();
    g.profile_value = profile->at("value").numbers();
    profile->finish();
    if (g.profile_deg.size() != g.profile_value.size())
      profile->fail("\"deg\" and \"value\" have different lengths");
    if (g.profile_deg.size() < 2) profile->fail("a profile needs at least two samples");
    double total = 0;
    for (size_t i = 0; i < g.profile_deg.size(); ++i) {
      double d = g.profile_deg[i], v = g.profile_value[i];
      if (d < 0 || d > g.cone_deg)
        profile->fail("angle " + std::to_string(d) + " is outside the cone");
      if (i > 0 && d <= g.profile_deg[i - 1]) profile->fail("angles must increase");
      if (v < 0) profile->fail("negative profile value at " + std::to_string(d) + " deg");
      total += v;
    }
    if (total <= 0) profile->fail("the profile is zero everywhere");
  }
  node.finish();
  return g;
}

// A dispersive index: a named glass, Sellmeier or Cauchy coefficients, or any spectrum value.
static SpectrumPtr parse_index_spectrum(const JsonNode& eta) {
  if (eta.is_string()) {
    SpectrumPtr glass = named_glass(eta.string());
    if (!glass) {
      std::string names;
      for (const std::string& n : named_glass_names()) names += (names.empty() ? "" : ", ") + n;
      eta.fail("unknown glass \"" + eta.string() + "\" (built in: " + names + ")");
    }
    return glass;
  }
  if (auto s = eta.find("sellmeier")) {
    std::vector<double> B = s->at("B").numbers(), C = s->at("C_um2").numbers();
    s->finish();
    eta.finish();
    if (B.empty() || B.size() != C.size() || B.size() > 8)
      s->fail("\"B\" and \"C_um2\" need the same number of terms, 1 to 8");
    return index_spectrum([B, C](double nm) { return sellmeier_index(B, C, nm); });
  }
  if (auto c = eta.find("cauchy")) {
    double A = c->at("A").number(), B = 0, C = 0;
    if (auto b = c->find("B_um2")) B = b->number();
    if (auto cc = c->find("C_um4")) C = cc->number();
    c->finish();
    eta.finish();
    return index_spectrum([A, B, C](double nm) { return cauchy_index(A, B, C, nm); });
  }
  return parse_spectrum(eta);
}

// A roughness key: a number in [0, 1], or {"texture": NAME}, one of the scene's textures whose
// value at each point is the roughness there (resolved by the scene).
static double roughness_value(const JsonNode& key, Roughness& r, int axis) {
  if (!key.is_object()) return key.number_in(0.0, 1.0);
  const JsonNode name = key.at("texture");
  r.texture_name[axis] = name.string();
  if (r.texture_name[axis].empty()) name.fail("expected a texture's name");
  r.where[axis] = key.where();
  key.finish();
  return 0;
}

// pbrt-v4's roughness parameters, each in [0, 1] or a texture's value.
static Roughness parse_roughness(const JsonNode& node) {
  Roughness r;
  double u = 0, v = 0;
  auto both = node.find("roughness"), ru = node.find("uroughness"), rv = node.find("vroughness");
  if (both && (ru || rv))
    both->fail("give \"roughness\" or \"uroughness\" and \"vroughness\", not both");
  if (both) {
    u = v = roughness_value(*both, r, 0);
    r.texture_name[1] = r.texture_name[0];
    r.where[1] = r.where[0];
  }
  if (ru) u = roughness_value(*ru, r, 0);
  if (rv) v = roughness_value(*rv, r, 1);
  if (auto remap = node.find("remap_roughness")) r.remap = remap->boolean();
  r.alpha_x = r.remap ? std::sqrt(u) : u;
  r.alpha_y = r.remap ? std::sqrt(v) : v;
  return r;
}

// {"eta": 1.5, "thickness": 0.01, "roughness": 0}: pbrt-v4's coateddiffuse defaults and keys. Its
// albedo and g (a scattering layer) and anisotropic roughness are not built: refused, not ignored.
static CoatDesc parse_coat(const JsonNode& node) {
  CoatDesc c;
  if (auto eta = node.find("eta")) {
    c.eta = eta->number();
    if (!(c.eta >= 0.01 && c.eta <= 100)) eta->fail("eta must lie in [0.01, 100]");
  }
  if (auto d = node.find("thickness")) c.thickness = d->number_in(0.0, 1e3);
  const Roughness r = parse_roughness(node);
  if (r.textured()) {
    // One texture for both axes: the scene reads it as its mean (resolve_coat_roughness).
    if (r.texture_name[0] != r.texture_name[1])
      node.fail("an anisotropic coat is not built: give \"roughness\" (one texture or number)");
    c.alpha_texture = r.texture_name[0];
    c.alpha_where = r.where[0];
    c.alpha_remap = r.remap;
  } else if (r.alpha_x != r.alpha_y)
    node.fail(
        "an anisotropic coat is not built: give \"roughness\" (or equal \"uroughness\" and "
        "\"vroughness\")");
  c.alpha = r.alpha_x;
  if (auto a = node.find("albedo"))
    if (!(a->number_in(0.0, 1.0) == 0))
      a->fail("a scattering coat (albedo above 0) is not built: the layer only absorbs");
  node.finish();
  return c;
}

// {"eta": 1.5}: pbrt-v4's default index; a spectral "eta" disperses.
static DielectricDesc parse_dielectric(const JsonNode& node) {
  DielectricDesc d;
  if (auto eta = node.find("eta")) {
    if (eta->is_number()) {
      d.eta = eta->number();
      if (!(d.eta >= 0.01 && d.eta <= 100))
        eta->fail(
            "eta must lie in [0.01, 100] (the index behind the surface over the one in front)");
    } else {
      d.eta_spectrum = parse_index_spectrum(*eta);
    }
  }
  if (auto thin = node.find("thin")) {
    d.thin = thin->boolean();
    if (d.thin && d.eta_spectrum) thin->fail("a thin dielectric's \"eta\" must be a number");
  }
  node.finish();
  return d;
}

// {"metal": "Au"}, or {"eta": SPECTRUM, "k": SPECTRUM}; {} is copper, as in pbrt-v4.
static ConductorDesc parse_conductor(const JsonNode& node) {
  ConductorDesc c;
  auto metal = node.find("metal");
  auto eta = node.find("eta"), k = node.find("k");
  if (metal && (eta || k)) metal->fail("give either \"metal\" or \"eta\" and \"k\", not both");
  if (eta || k) {
    if (!eta) node.fail("\"k\" without \"eta\"");
    if (!k) node.fail("\"eta\" without \"k\"");
    c.eta = parse_spectrum(*eta);
    c.k = parse_spectrum(*k);
  } else {
    c.metal = metal ? metal->string() : "Cu";
    MetalIndex index = builtin_metal(c.metal);
    if (!index.eta) {
      std::string names;
      for (const std::string& n : builtin_metal_names()) names += (names.empty() ? "" : ", ") + n;
      metal->fail("unknown metal \"" + c.metal + "\" (built in: " + names + ")");
    }
    c.eta = index.eta;
    c.k = index.k;
  }
  node.finish();
  return c;
}

void apply_coat(MaterialDesc& m, const JsonNode& coat) {
  if (m.kind == MaterialKind::mix) coat.fail("a mix takes no coat (its materials may)");
  if (m.kind == MaterialKind::dielectric) coat.fail("a dielectric takes no coat");
  if (m.gloss) coat.fail("a coated material has no \"gloss\" part: the coat is its gloss");
  m.coat = parse_coat(coat);
  // Both smooth, the layer's walk stays on the mirror direction and sums in closed form
  // (docs/materials.md#coated-conductors); either rough, the scene splits it into parts
  // (material/layered_metal.h), which take one roughness for the metal.
  if (m.kind == MaterialKind::conductor && m.roughness.textured())
    coat.fail(
        "a conductor under a coat takes a roughness number, not a texture (the layer's tables "
        "are made for one)");
}

// {"transmittance": SPECTRUM, "scale": k}: Lambert transmission beside the passive reflectance
// (pbrt-v4's DiffuseTransmissionBxDF); without a "passive" part the reflectance is 0.
static void parse_transmission(const JsonNode& node, MaterialDesc& m) {
  m.transmittance = parse_spectrum(node.at("transmittance"));
  if (auto scale = node.find("scale")) m.transmission_scale = scale->number_in(0.0, 1e3);
  node.finish();
  if (!m.passive) m.passive = std::make_shared<ConstantSpectrum>(0.0);
}

MaterialDesc parse_material(const JsonNode& node, const std::string& name) {
  MaterialDesc m;
  m.name = name;
  m.where = node.where();
  if (auto version = node.find("kasha_material")) {
    if (version->integer_in(0, 1000) != 1) version->fail("unsupported material version");
  }
  if (auto n = node.find("name")) {
    std::string own = n->string();
    if (m.name.empty()) m.name = own;
  }
  if (auto passive = node.find("passive")) {
    m.passive = parse_spectrum(passive->at("reflectance"));
    passive->finish();
  }
  if (auto fluo = node.find("fluorescence")) {
    m.excitation = parse_spectrum(fluo->at("excitation"));
    m.emission = parse_spectrum(fluo->at("emission"));
    fluo->finish();
  }
  if (auto gloss = node.find("gloss")) m.gloss = parse_gloss(*gloss);
  if (auto transmission = node.find("transmission")) parse_transmission(*transmission, m);
  if (auto coat = node.find("coat")) {
    if (node.has("dielectric")) coat->fail("a dielectric takes no coat");
    if (!node.has("conductor")) apply_coat(m, *coat);
  }
  auto dielectric = node.find("dielectric"), conductor = node.find("conductor");
  if (dielectric || conductor) {
    const JsonNode& own = dielectric ? *dielectric : *conductor;
    if (dielectric && conductor) own.fail("a material is a dielectric or a conductor, not both");
    if (m.passive || m.excitation || m.gloss || m.transmittance)
      own.fail(
          "a dielectric or conductor has no \"passive\", \"fluorescence\", \"gloss\" or "
          "\"transmission\" part");
    m.roughness = parse_roughness(own);
    if (dielectric) {
      m.kind = MaterialKind::dielectric;
      m.dielectric = parse_dielectric(*dielectric);
      if (m.dielectric.thin && m.roughness.rough())
        dielectric->fail("a thin dielectric is smooth: it takes no roughness");
    } else {
      m.kind = MaterialKind::conductor;
      m.conductor = parse_conductor(*conductor);
      if (auto coat = node.find("coat")) apply_coat(m, *coat);
    }
  }
  if (auto mix = node.find("mix")) {
    // A mix is only its two materials: their parts are theirs.
    for (const char* part :
         {"passive", "fluorescence", "gloss", "transmission", "coat", "dielectric", "conductor"})
      if (node.has(part))
        mix->fail(std::string("a mix has no \"") + part + "\" part of its own (its materials do)");
    m.kind = MaterialKind::mix;
    m.mix = parse_mix(*mix);
  }
  node.find("diagnostics");  // written by `kasha measure`, ignored on load
  node.finish();
  return m;
}

MaterialDesc load_material_file(const std::string& path, const std::string& name) {
  JsonNode root = JsonNode::load_file(path);
  if (!root.is_object()) root.fail("expected a material object");
  if (!root.has("kasha_material"))
    root.fail("missing \"kasha_material\": 1 (not a kasha material file)");
  if (auto mix = root.find("mix"))
    mix->fail("a material file cannot hold a mix (it names a scene's materials)");
  return parse_material(root, name);
}

static std::string nm_text(double nm) {
  std::ostringstream o;
  o << nm << " nm";
  return o.str();
}

// τ on the grid, and the transmission's scale applied to ρ and τ alike (after ρ's own check, as
// pbrt-v4 scales its reflectance and transmittance). A coat or gloss lobe over it is refused.
static void discretize_transmission(const MaterialDesc& desc, const WavelengthGrid& grid,
                                    const std::string& who, Material& m) {
  if (desc.coat || desc.gloss || desc.excitation)
    throw Error(who + ": a \"transmission\" part takes no coat, gloss or fluorescence");
  m.tau = grid.resample(*desc.transmittance);
  for (int i = 0; i < grid.bins; ++i) {
    if (!(m.tau[i] >= 0))
      throw Error(who + ": transmittance " + std::to_string(m.tau[i]) + " < 0 at " +
                  nm_text(grid.center(i)));
    m.tau[i] *= desc.transmission_scale;
    m.rho[i] *= desc.transmission_scale;
  }
}

Material discretize_material(const MaterialDesc& desc, const WavelengthGrid& grid) {
  Material m;
  m.name = desc.name;
  m.gloss = desc.gloss;
  m.coat = desc.coat;
  m.mix = desc.mix;
  m.under_coat = desc.under_coat;
  m.layer_scale = desc.layer_scale;
  m.kind = desc.kind;
  m.eta = desc.dielectric.eta;
  m.thin = desc.dielectric.thin;
  m.roughness = desc.roughness;
  const std::string who = "material '" + desc.name + "' (" + desc.where + ")";
  if (desc.dielectric.eta_spectrum) {
    m.eta_bins = grid.resample(*desc.dielectric.eta_spectrum);
    for (int i = 0; i < grid.bins; ++i)
      if (!(m.eta_bins[i] >= 0.01 && m.eta_bins[i] <= 100))
        throw Error(who + ": dielectric eta " + std::to_string(m.eta_bins[i]) + " at " +
                    nm_text(grid.center(i)) + " is outside [0.01, 100] (does the spectrum cover " +
                    grid.describe() + "?)");
    m.eta = m.eta_bins[grid.bins / 2];
    // The same index in every bin is no dispersion: the kernels need no bin choice for it.
    if (std::all_of(m.eta_bins.begin(), m.eta_bins.end(),
                    [&](double e) { return std::abs(e - m.eta) <= 1e-9 * m.eta; }))
      m.eta_bins.clear();
  }
  if (desc.kind == MaterialKind::conductor) {
    m.eta_c = grid.resample(*desc.conductor.eta);
    m.k_c = grid.resample(*desc.conductor.k);
    for (int i = 0; i < grid.bins; ++i) {
      if (!(m.eta_c[i] >= 1e-3))
        throw Error(who + ": conductor eta " + std::to_string(m.eta_c[i]) + " at " +
                    nm_text(grid.center(i)) + " is not above 0.001 (does the spectrum cover " +
                    grid.describe() + "?)");
      if (m.eta_c[i] > 1e3 || m.k_c[i] > 1e3)
        throw Error(who + ": conductor eta or k beyond 1000 at " + nm_text(grid.center(i)));
    }
  }
  if (desc.passive) {
    m.rho = grid.resample(*desc.passive);
    for (int i = 0; i < grid.bins; ++i)
      if (m.rho[i] > 1.0 + 1e-9)
        throw Error(who + ": passive reflectance " + std::to_string(m.rho[i]) + " > 1 at " +
                    nm_text(grid.center(i)));
  }
  if (desc.excitation) {
    m.a = grid.resample(*desc.excitation);
    std::vector<double> e = grid.resample(*desc.emission);
    double total = 0;
    for (double v : e) total += v * grid.bin_nm;
    if (!(total > 0)) throw Error(who + ": fluorescence emission is zero over " + grid.describe());
    m.e_hat.resize(grid.bins);
    for (int i = 0; i < grid.bins; ++i) m.e_hat[i] = e[i] * grid.bin_nm / total;
    for (int i = 0; i < grid.bins; ++i)
      if (m.a[i] > 1.0 + 1e-9)
        throw Error(who + ": excitation " + std::to_string(m.a[i]) + " > 1 at " +
                    nm_text(grid.center(i)));
  }
  if (desc.transmittance) discretize_transmission(desc, grid, who, m);
  double g = m.gloss_reflectance();
  for (int i = 0; i < grid.bins; ++i) {
    double rho = m.rho.empty() ? 0 : m.rho[i], a = m.a.empty() ? 0 : m.a[i];
    double tau = m.tau.empty() ? 0 : m.tau[i];
    if (g + rho + a + tau > 1.0 + 1e-6) {
      std::ostringstream msg;
      msg << who << ": energy gain at " << nm_text(grid.center(i)) << ": gloss " << g
          << " + passive " << rho << " + excitation " << a;
      if (!m.tau.empty()) msg << " + transmittance " << tau;
      msg << " = " << g + rho + a + tau << " > 1";
      throw Error(msg.str());
    }
  }
  return m;
}

}  // namespace kasha
