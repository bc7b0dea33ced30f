#include "material/material.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
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

MaterialDesc parse_material(const JsonNode& node, const std::string& name) {
  MaterialDesc m;
  m.name = name;
  m.where = node.file() + ": " + node.path();
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
  node.find("diagnostics");  // written by `kasha measure`, ignored on load
  node.finish();
  return m;
}

MaterialDesc load_material_file(const std::string& path, const std::string& name) {
  JsonNode root = JsonNode::load_file(path);
  if (!root.is_object()) root.fail("expected a material object");
  if (!root.has("kasha_material"))
    root.fail("missing \"kasha_material\": 1 (not a kasha material file)");
  return parse_material(root, name);
}

static std::string nm_text(double nm) {
  std::ostringstream o;
  o << nm << " nm";
  return o.str();
}

Material discretize_material(const MaterialDesc& desc, const WavelengthGrid& grid) {
  Material m;
  m.name = desc.name;
  m.gloss = desc.gloss;
  const std::string who = "material '" + desc.name + "' (" + desc.where + ")";
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
  double g = m.gloss_reflectance();
  for (int i = 0; i < grid.bins; ++i) {
    double rho = m.rho.empty() ? 0 : m.rho[i], a = m.a.empty() ? 0 : m.a[i];
    if (g + rho + a > 1.0 + 1e-6) {
      std::ostringstream msg;
      msg << who << ": energy gain at " << nm_text(grid.center(i)) << ": gloss " << g
          << " + passive " << rho << " + excitation " << a << " = " << g + rho + a << " > 1";
      throw Error(msg.str());
    }
  }
  return m;
}

}  // namespace kasha
