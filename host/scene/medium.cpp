#include "scene/medium.h"

#include <cmath>

#include "core/error.h"
#include "core/printable.h"
#include "scene/colour_grid.h"
#include "scene/transform.h"
#include "scene/vdb_grid.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

bool Medium::scatters() const {
  for (double s : sigma_s)
    if (s > 0) return true;
  return !fluorophores.empty() || !emission.empty();
}

// A dye file ({"kasha_dye": 1, ...}): a dye's "molar_absorption", "emission" and
// "quantum_yield" as measured in one solvent, with "name", "solvent" and "source" for people;
// the scene gives the concentration. Its "csv" paths resolve against the dye file's folder.
static void read_dye_file(const JsonNode& entry, FluorophoreDesc& f) {
  const std::filesystem::path p = entry.at("dye").file_path();
  const JsonNode dye = JsonNode::load_file(p);
  if (!dye.is_object()) dye.fail("expected a dye object");
  if (!dye.has("kasha_dye")) dye.fail("missing \"kasha_dye\": 1 (not a kasha dye file)");
  if (dye.at("kasha_dye").integer_in(0, 1000) != 1)
    dye.at("kasha_dye").fail("unsupported dye version");
  for (const char* key : {"name", "solvent", "source"})
    if (auto text = dye.find(key)) text->string();
  f.absorption = parse_spectrum(dye.at("molar_absorption"));
  f.emission = parse_spectrum(dye.at("emission"));
  f.quantum_yield = dye.at("quantum_yield").number_in(0, 1);
  dye.finish();
  for (const char* key : {"absorption", "molar_absorption", "emission"})
    if (auto own = entry.find(key))
      own->fail(std::string("a fluorophore with a \"dye\" file takes its \"") + key + "\" from it");
}

// One entry of a medium's "fluorophores": "absorption" (per scene unit of length), or
// "molar_absorption" (decadic, L·mol⁻¹·cm⁻¹) with "concentration" (mol·L⁻¹) and "unit_cm" (the
// scene's unit of length in cm, 100: metres), or a "dye" file with "concentration";
// "quantum_yield" in [0, 1] (a dye file's unless given); "emission".
static FluorophoreDesc parse_fluorophore(const JsonNode& node) {
  if (!node.is_object()) node.fail("expected a fluorophore object");
  FluorophoreDesc f;
  f.where = node.where();
  auto absorption = node.find("absorption"), molar = node.find("molar_absorption");
  const bool dye = node.has("dye");
  if (absorption && molar) molar->fail("give \"absorption\" or \"molar_absorption\", not both");
  if (dye) read_dye_file(node, f);
  if (absorption) {
    f.absorption = parse_spectrum(*absorption);
  } else if (molar || dye) {
    const double c = node.at("concentration").number_in(0, 1e3);
    double unit_cm = 100;
    if (auto u = node.find("unit_cm")) unit_cm = u->number_in(1e-12, 1e12);
    // Decadic absorbance per cm, ε c, as natural attenuation per scene unit: ln 10 · ε c · unit.
    if (molar) f.absorption = parse_spectrum(*molar);
    f.absorption_scale = std::log(10.0) * c * unit_cm;
  } else {
    node.fail(
        "a fluorophore needs its \"absorption\" (or \"molar_absorption\" and \"concentration\", or "
        "a \"dye\" file and \"concentration\")");
  }
  if (node.has("quantum_yield")) f.quantum_yield = node.at("quantum_yield").number_in(0, 1);
  if (!dye) f.emission = parse_spectrum(node.at("emission"));
  node.finish();
  return f;
}

// A grid read from an OpenVDB file: {"vdb": FILE, "grid": NAME ("density")}; its own map from
// index to the medium's space, then the medium's "transform" to the world's. No "bounds".
static DensityGrid parse_vdb_density(const JsonNode& node, const JsonNode& density) {
  const JsonNode file = density.at("vdb");
  const std::filesystem::path p = file.file_path();
  const std::string name = density.has("grid") ? density.at("grid").string() : "density";
  density.finish();
  if (auto b = node.find("bounds")) b->fail("an OpenVDB grid's bounds are its own");
  DensityGrid g = read_vdb_density(p.string(), file.where() + ": " + printable(p.string()), name);
  g.file_map = g.to_world;
  if (auto t = node.find("transform")) {
    const Eigen::Affine3d to_world = parse_transform(*t);
    if (std::abs(to_world.linear().determinant()) < 1e-12) t->fail("the transform is singular");
    g.to_world = to_world * g.to_world;
  }
  return g;
}

// A lattice's "size": [nx, ny, nz], each in [1, 4096], at most 2^28 samples.
static void parse_lattice_size(const JsonNode& size, DensityGrid& g) {
  const std::vector<double> n = size.numbers();
  if (n.size() != 3) size.fail("expected [nx, ny, nz]");
  for (double v : n)
    if (!(v >= 1 && v <= 4096 && v == std::floor(v)))
      size.fail("each size must be a whole number in [1, 4096]");
  g.nx = static_cast<int>(n[0]), g.ny = static_cast<int>(n[1]), g.nz = static_cast<int>(n[2]);
  if (n[0] * n[1] * n[2] > static_cast<double>(1 << 28))
    size.fail("a grid holds at most 2^28 samples");
}

// "A x B x C", a lattice's size in messages.
static std::string lattice_text(const DensityGrid& g) {
  return std::to_string(g.nx) + " x " + std::to_string(g.ny) + " x " + std::to_string(g.nz);
}

// `values`: `want` numbers, each in [lo, 1e30], as floats; a wrong count fails with `count`
// followed by " N values, not M", a value out of range with `bad`.
static std::vector<float> sample_values(const JsonNode& values, size_t want, const std::string& count,
                                        double lo, const char* bad) {
  const std::vector<double> v = values.numbers();
  if (v.size() != want)
    values.fail(count + " " + std::to_string(want) + " values, not " + std::to_string(v.size()));
  std::vector<float> out;
  out.reserve(v.size());
  for (double x : v) {
    if (!(x >= lo && x <= 1e30)) values.fail(bad);
    out.push_back(static_cast<float>(x));
  }
  return out;
}

// A grid medium's "bounds": {"min", "max"} (default the unit cube) and "transform" (the medium's
// space to the world's).
static void parse_grid_box(const JsonNode& node, DensityGrid& g) {
  if (auto b = node.find("bounds")) {
    const auto lo = b->at("min").vec3(), hi = b->at("max").vec3();
    g.p0 = {lo[0], lo[1], lo[2]}, g.p1 = {hi[0], hi[1], hi[2]};
    if (!(g.p0.array() < g.p1.array()).all()) b->fail("each of \"min\" must be below \"max\"");
    b->finish();
  }
  if (auto t = node.find("transform")) {
    g.to_world = parse_transform(*t);
    if (std::abs(g.to_world.linear().determinant()) < 1e-12) t->fail("the transform is singular");
  }
}

// A "grid" medium's "density": {"size": [nx, ny, nz], "values": [...]}, "bounds" and "transform"
// (parse_grid_box).
static DensityGrid parse_density_grid(const JsonNode& node) {
  DensityGrid g;
  if (!node.has("density")) node.fail("a grid medium needs its \"density\"");
  const JsonNode density = node.at("density");
  if (!density.is_object())
    density.fail("expected {\"size\": [nx, ny, nz], \"values\": [...]} or {\"vdb\": FILE}");
  if (density.has("vdb")) return parse_vdb_density(node, density);
  parse_lattice_size(density.at("size"), g);
  g.values = sample_values(density.at("values"), static_cast<size_t>(g.nx) * g.ny * g.nz,
                           "a grid of " + lattice_text(g) + " needs", 0,
                           "a density must be finite and not negative");
  density.finish();
  parse_grid_box(node, g);
  return g;
}

// An "rgbgrid" medium (scene/colour_grid.h): "size", σa's and σs's {"rgb_values": [r, g, b, ...]}
// (linear sRGB, 3 per sample, x fastest; either may be left out: 1 in the whole box, not both),
// "bounds" and "transform".
static DensityGrid parse_colour_grid(const JsonNode& node) {
  DensityGrid g;
  parse_lattice_size(node.at("size"), g);
  const size_t want = 3 * static_cast<size_t>(g.nx) * g.ny * g.nz;
  for (const char* key : {"sigma_a", "sigma_s"}) {
    auto c = node.find(key);
    if (!c) continue;
    if (!c->is_object() || !c->has("rgb_values"))
      c->fail("expected {\"rgb_values\": [r, g, b, ...]}, a colour per sample");
    const JsonNode values = c->at("rgb_values");
    c->finish();
    (key[6] == 'a' ? g.sigma_a_rgb : g.sigma_s_rgb) =
        sample_values(values, want, "a grid of " + lattice_text(g) + " needs", 0,
                      "a colour must be finite and not negative");
  }
  if (g.sigma_a_rgb.empty() && g.sigma_s_rgb.empty())
    node.fail("an rgbgrid needs \"sigma_a\" or \"sigma_s\" colours");
  if (auto e = node.find("emission")) {
    // It emits σa·Le: pbrt-v4 refuses an "Le" without "sigma_a".
    if (g.sigma_a_rgb.empty())
      e->fail("an rgbgrid emits σa·Le: its emission needs \"sigma_a\" colours");
    if (!e->is_object() || !e->has("rgb_values"))
      e->fail("expected {\"rgb_values\": [r, g, b, ...]}, a colour per sample");
    const JsonNode values = e->at("rgb_values");
    e->finish();
    g.emission_rgb = sample_values(values, want, "a grid of " + lattice_text(g) + " needs", 0,
                                   "a colour must be finite and not negative");
  }
  parse_grid_box(node, g);
  return g;
}

// Values on a grid medium's samples: {"values": [...]} (one per sample, x fastest) or, for a grid
// from a VDB file, {"vdb": FILE, "grid": NAME}, a grid of a file whose voxels line up with the
// density's (the same index-to-world map). Each in [lo, 1e30].
static std::vector<float> parse_lattice_values(const JsonNode& node, const DensityGrid& lattice,
                                               double lo) {
  if (!node.is_object())
    node.fail("expected {\"values\": [...]} or {\"vdb\": FILE, \"grid\": NAME}");
  if (node.has("vdb")) {
    const JsonNode file = node.at("vdb");
    const std::filesystem::path p = file.file_path();
    const JsonNode grid = node.at("grid");
    node.finish();
    return read_vdb_on_lattice(p.string(), file.where() + ": " + printable(p.string()),
                               grid.string(), lattice);
  }
  const JsonNode values = node.at("values");
  node.finish();
  return sample_values(values, static_cast<size_t>(lattice.nx) * lattice.ny * lattice.nz,
                       "the density's " + lattice_text(lattice) + " samples need", lo,
                       lo == 0 ? "a value must be finite and not negative" : "a value must be finite");
}

// A medium's emission beyond "emission" (docs/media.md#emitting-grids): "emission_scale" (a
// number, or a grid's values) and a grid's "temperature" with "temperature_offset" and
// "temperature_scale".
static void parse_emission_grids(const JsonNode& node, MediumDesc& d) {
  if (auto t = node.find("temperature")) {
    if (!d.grid) t->fail("a temperature needs a grid medium");
    if (node.has("emission"))
      t->fail(
          "a medium emits a spectrum (\"emission\") or a blackbody (\"temperature\"), not both");
    d.grid->temperature = parse_lattice_values(*t, *d.grid, -1e30);
    d.blackbody = Blackbody{};
    if (auto o = node.find("temperature_offset")) d.blackbody->offset = o->number_in(-1e30, 1e30);
    if (auto c = node.find("temperature_scale")) d.blackbody->scale = c->number_in(0, 1e30);
  } else {
    for (const char* key : {"temperature_offset", "temperature_scale"})
      if (auto k = node.find(key)) k->fail("only with a \"temperature\"");
  }
  if (auto e = node.find("emission_scale")) {
    if (!node.has("emission") && !d.blackbody)
      e->fail("scales a medium's \"emission\" or \"temperature\", which it has not");
    if (e->is_number()) {
      d.emission_scale = e->number_in(0, 1e30);
    } else {
      if (!d.grid) e->fail("a grid of emission scales needs a grid medium");
      if (d.grid->coloured())
        e->fail("an rgbgrid's emission scale is a number (pbrt-v4's Lescale)");
      d.grid->emission_scale = parse_lattice_values(*e, *d.grid, 0);
    }
  }
}

MediumDesc parse_medium(const JsonNode& node, const std::string& name) {
  if (!node.is_object()) node.fail("expected a medium object");
  MediumDesc d;
  d.name = name;
  d.where = node.where();
  const std::string type = node.has("type") ? node.at("type").string() : "homogeneous";
  if (type != "homogeneous" && type != "grid" && type != "rgbgrid")
    node.at("type").fail("unknown medium type \"" + type + "\" (homogeneous, grid, rgbgrid)");
  if (type == "grid") d.grid = parse_density_grid(node);
  if (type == "rgbgrid") {
    d.grid = parse_colour_grid(node);
    for (const char* key : {"fluorophores", "temperature"})
      if (auto k = node.find(key))
        k->fail("an rgbgrid medium takes no \"" + std::string(key) + "\"");
  }
  // pbrt-v4's defaults: σa = σs = 1, scale 1, g 0.
  const auto coefficient = [&](const char* key) -> SpectrumPtr {
    if (auto c = node.find(key)) return parse_spectrum(*c);
    return std::make_shared<ConstantSpectrum>(1.0);
  };
  // An rgbgrid's colours are its grid's; its spectra stay pbrt-v4's 1 (unused).
  d.sigma_a = type == "rgbgrid" ? std::make_shared<ConstantSpectrum>(1.0) : coefficient("sigma_a");
  d.sigma_s = type == "rgbgrid" ? std::make_shared<ConstantSpectrum>(1.0) : coefficient("sigma_s");
  if (auto s = node.find("scale")) d.scale = s->number_in(0, 1e30);
  if (auto fl = node.find("fluorophores")) {
    if (!fl->is_array()) fl->fail("expected an array of fluorophores");
    if (fl->size() > static_cast<size_t>(kMaxMediumFluorophores))
      fl->fail("a medium holds at most " + std::to_string(kMaxMediumFluorophores) + " fluorophores");
    for (size_t k = 0; k < fl->size(); ++k) d.fluorophores.push_back(parse_fluorophore((*fl)[k]));
  }
  if (auto g = node.find("g")) {
    d.g = g->number();
    if (!(std::abs(d.g) < 1)) g->fail("the phase function's g must lie strictly between -1 and 1");
  }
  if (auto e = node.find("emission"); e && type != "rgbgrid") d.emission = parse_spectrum(*e);
  parse_emission_grids(node, d);
  node.finish();
  return d;
}

int medium_index(const JsonNode& node, const std::vector<MediumDesc>& media) {
  if (node.is_null()) return -1;
  const std::string name = node.string();
  if (name.empty()) return -1;
  for (size_t i = 0; i < media.size(); ++i)
    if (media[i].name == name) return static_cast<int>(i);
  node.fail("no medium named \"" + name + "\" in the scene's \"media\"");
}

MediumInterface parse_medium_interface(const JsonNode& node, const std::vector<MediumDesc>& media) {
  if (!node.is_object()) node.fail("expected {\"inside\": MEDIUM, \"outside\": MEDIUM}");
  MediumInterface mi;
  if (auto in = node.find("inside")) mi.inside = medium_index(*in, media);
  if (auto out = node.find("outside")) mi.outside = medium_index(*out, media);
  node.finish();
  return mi;
}

// A colour grid's components, and as its sigma_a and sigma_s their mean over the samples: what
// a collision does on average (vcm's pseudo-densities, whether it scatters at all).
static void colour_grid_means(Medium& m, double scale, const WavelengthGrid& grid) {
  m.components = colour_grid_components(*m.grid, scale, grid);
  m.sigma_a.assign(grid.bins, 0.0);
  m.sigma_s.assign(grid.bins, 0.0);
  for (const GridComponent& k : m.components) {
    double mean = 1;
    if (!k.values.empty()) {
      double sum = 0;
      for (float v : k.values) sum += v;
      mean = sum / static_cast<double>(k.values.size());
    }
    for (int i = 0; i < grid.bins; ++i) {
      m.sigma_a[i] += mean * (k.sigma_t[i] - k.sigma_s[i]);
      m.sigma_s[i] += mean * k.sigma_s[i];
    }
  }
  m.grid->sigma_a_rgb.clear();
  m.grid->sigma_s_rgb.clear();
}

// An emitting colour grid's radiance as components, and as its `emission` mean σa times mean Le
// (what the light paths' share of the power is reckoned from, docs/media.md#emitting-media).
static void colour_grid_emission_means(Medium& m, double scale, const WavelengthGrid& grid) {
  m.emission_components = colour_grid_emission(*m.grid, scale, grid);
  m.grid->emission_rgb.clear();
  if (m.emission_components.empty()) return;
  std::vector<double> le(grid.bins, 0.0);
  for (const EmissionComponent& k : m.emission_components) {
    double sum = 0;
    for (float v : k.values) sum += v;
    for (int i = 0; i < grid.bins; ++i)
      le[i] += sum / static_cast<double>(k.values.size()) * k.radiance[i];
  }
  double total = 0;
  for (int i = 0; i < grid.bins; ++i) total += m.emission.emplace_back(m.sigma_a[i] * le[i]);
  if (!(total > 0)) m.emission.clear(), m.emission_components.clear();
}

Medium discretize_medium(const MediumDesc& desc, const WavelengthGrid& grid) {
  Medium m;
  m.sigma_a = grid.resample(*desc.sigma_a);
  m.sigma_s = grid.resample(*desc.sigma_s);
  for (double& v : m.sigma_a) v *= desc.scale;
  for (double& v : m.sigma_s) v *= desc.scale;
  m.g = desc.g;
  m.grid = desc.grid;
  if (desc.grid && desc.grid->coloured()) {
    colour_grid_means(m, desc.scale, grid);
    if (!desc.grid->emission_rgb.empty()) colour_grid_emission_means(m, desc.emission_scale, grid);
  }
  if (desc.emission || desc.blackbody) {
    // Emitted radiance per unit length: σa·Le (pbrt-v4's), nothing where the medium absorbs
    // nothing; a blackbody's spectrum is the kernels' to evaluate at each point's temperature.
    const std::vector<double> le =
        desc.emission ? grid.resample(*desc.emission) : std::vector<double>(grid.bins, 1.0);
    double total = 0;
    for (size_t i = 0; i < le.size(); ++i) {
      if (!(le[i] >= 0)) throw Error(desc.where + "/emission: a negative or non-finite radiance");
      m.emission.push_back(m.sigma_a[i] * le[i] * desc.emission_scale);
      total += m.emission.back();
    }
    if (!(total > 0)) m.emission.clear();
    if (!m.emission.empty()) m.blackbody = desc.blackbody;
  }
  for (const FluorophoreDesc& fd : desc.fluorophores) {
    Fluorophore f;
    f.absorption = grid.resample(*fd.absorption);
    for (double& v : f.absorption) v *= fd.absorption_scale;
    f.quantum_yield = fd.quantum_yield;
    const std::vector<double> e = grid.resample(*fd.emission);
    double total = 0;
    for (double v : e) total += v;
    if (!(total > 0))
      throw Error(fd.where + "/emission: no emission on the wavelength grid " + grid.describe());
    for (double v : e) f.e_hat.push_back(v / total);
    m.fluorophores.push_back(f);
  }
  return m;
}

}  // namespace kasha
