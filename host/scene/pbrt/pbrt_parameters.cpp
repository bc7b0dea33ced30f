#include "scene/pbrt/pbrt_parameters.h"

#include <array>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/printable.h"
#include "core/warning.h"

namespace kasha {

void pbrt_fail(const PbrtLocation& where, const std::string& why) {
  throw Error(where.str() + ": " + why);
}

std::string in_quotes(const std::string& s) {
  return "\"" + printable(s) + "\"";
}

void pbrt_warn(const PbrtLocation& where, const std::string& why) {
  warn(where.str() + ": " + why);
}

size_t PbrtParameter::count() const {
  return numbers.size() + strings.size() + bools.size();
}

namespace {

// pbrt-v4's type names and their older spellings.
std::string canonical_type(const std::string& t) {
  if (t == "point") return "point3";
  if (t == "vector") return "vector3";
  if (t == "normal") return "normal3";
  if (t == "color") return "rgb";
  for (const char* known : {"integer", "float", "point2", "vector2", "point3", "vector3", "normal3",
                            "spectrum", "rgb", "blackbody", "bool", "string", "texture"})
    if (t == known) return t;
  return "";
}

double parse_number(const PbrtToken& t, const std::string& declaration) {
  const char* s = t.text.c_str();
  char* end = nullptr;
  double v = std::strtod(s, &end);
  if (t.text.empty() || *end != '\0' || !std::isfinite(v))
    pbrt_fail(t.where, "\"" + printable(declaration) + "\": \"" + printable(t.text) +
                           "\" is not a finite number");
  return v;
}

void add_value(PbrtParameter& p, const PbrtToken& t) {
  const std::string& type = p.type;
  if (type == "bool") {
    if (t.text == "true")
      p.bools.push_back(true);
    else if (t.text == "false")
      p.bools.push_back(false);
    else
      pbrt_fail(t.where, "\"" + printable(p.declaration()) + "\": \"" + printable(t.text) +
                             "\" is not true or false");
  } else if (type == "string" || type == "texture") {
    if (t.kind != PbrtToken::kString)
      pbrt_fail(t.where, "\"" + printable(p.declaration()) + "\" takes quoted strings");
    p.strings.push_back(t.text);
  } else if (type == "spectrum" && t.kind == PbrtToken::kString) {
    p.strings.push_back(t.text);
  } else {
    if (t.kind != PbrtToken::kWord)
      pbrt_fail(t.where, "\"" + printable(p.declaration()) + "\" takes numbers");
    p.numbers.push_back(parse_number(t, p.declaration()));
  }
  if (!p.strings.empty() && !p.numbers.empty())
    pbrt_fail(t.where, "\"" + printable(p.declaration()) + "\" mixes numbers and names");
}

// The number of values each numeric type comes in groups of.
size_t group_size(const std::string& type) {
  if (type == "point2" || type == "vector2") return 2;
  if (type == "point3" || type == "vector3" || type == "normal3" || type == "rgb") return 3;
  return 1;
}

}  // namespace

PbrtParameters PbrtParameters::read(PbrtTokenizer& tokens) {
  PbrtParameters out;
  for (;;) {
    PbrtToken decl = tokens.next();
    if (decl.kind != PbrtToken::kString) {
      tokens.put_back(std::move(decl));
      return out;
    }
    std::istringstream words(decl.text);
    std::string type, name, extra;
    words >> type >> name >> extra;
    if (name.empty() || !extra.empty())
      pbrt_fail(decl.where,
                "\"" + printable(decl.text) + "\" is not a parameter declaration (\"type name\")");
    PbrtParameter p;
    p.type = canonical_type(type);
    if (p.type.empty())
      pbrt_fail(decl.where, "\"" + printable(decl.text) + "\": unknown parameter type \"" +
                                printable(type) + "\"");
    p.name = name;
    p.where = decl.where;
    for (const PbrtParameter& q : out.params_)
      if (q.name == name)
        pbrt_fail(decl.where, "parameter \"" + printable(name) + "\" given twice");
    PbrtToken v = tokens.next();
    if (v.kind == PbrtToken::kOpen) {
      for (;;) {
        PbrtToken e = tokens.next();
        if (e.kind == PbrtToken::kClose) break;
        if (e.kind == PbrtToken::kEnd || e.kind == PbrtToken::kOpen)
          pbrt_fail(e.where, "\"" + printable(p.declaration()) + "\": a list without its \"]\"");
        add_value(p, e);
      }
    } else if (v.kind == PbrtToken::kWord || v.kind == PbrtToken::kString) {
      add_value(p, v);
    } else {
      pbrt_fail(v.where, "\"" + printable(p.declaration()) + "\" has no value");
    }
    if (p.count() == 0) pbrt_fail(decl.where, "\"" + printable(p.declaration()) + "\" is empty");
    if (!p.numbers.empty() && p.numbers.size() % group_size(p.type) != 0)
      pbrt_fail(decl.where, "\"" + printable(p.declaration()) +
                                "\" needs its values in groups of " +
                                std::to_string(group_size(p.type)));
    if (p.type == "spectrum" && !p.numbers.empty() && p.numbers.size() % 2 != 0)
      pbrt_fail(decl.where, "\"" + printable(p.declaration()) + "\" needs wavelength-value pairs");
    out.params_.push_back(std::move(p));
  }
}

const PbrtParameter* PbrtParameters::find(const std::string& name, const std::string& types) const {
  for (const PbrtParameter& p : params_) {
    if (p.name != name) continue;
    std::istringstream list(types);
    std::string t;
    bool ok = false;
    while (list >> t) ok = ok || t == p.type;
    if (!ok)
      pbrt_fail(p.where, "\"" + printable(p.declaration()) + "\": \"" + printable(name) +
                             "\" takes a value of type " + types);
    p.used = true;
    return &p;
  }
  return nullptr;
}

static const PbrtParameter* one_value(const PbrtParameters& list, const std::string& name,
                                      const std::string& types) {
  const PbrtParameter* p = list.find(name, types);
  if (p && p->count() != 1)
    pbrt_fail(p->where, "\"" + printable(p->declaration()) + "\" takes one value, not " +
                            std::to_string(p->count()));
  return p;
}

double PbrtParameters::get_float(const std::string& name, double fallback) const {
  const PbrtParameter* p = one_value(*this, name, "float");
  return p ? p->numbers[0] : fallback;
}

int PbrtParameters::get_int(const std::string& name, int fallback) const {
  const PbrtParameter* p = one_value(*this, name, "integer");
  if (!p) return fallback;
  const double v = p->numbers[0];
  if (v != std::floor(v) || std::abs(v) > 2e9)
    pbrt_fail(p->where, "\"" + printable(p->declaration()) + "\" is not an integer");
  return static_cast<int>(v);
}

bool PbrtParameters::get_bool(const std::string& name, bool fallback) const {
  const PbrtParameter* p = find(name, "bool");
  if (!p) return fallback;
  if (p->bools.size() != 1)
    pbrt_fail(p->where, "\"" + printable(p->declaration()) + "\" takes one value");
  return p->bools[0];
}

std::string PbrtParameters::get_string(const std::string& name, const std::string& fallback) const {
  const PbrtParameter* p = one_value(*this, name, "string");
  return p ? p->strings[0] : fallback;
}

std::optional<std::array<double, 3>> PbrtParameters::get_triple(const std::string& name) const {
  const PbrtParameter* p = find(name, "point3 vector3 normal3");
  if (!p) return std::nullopt;
  if (p->numbers.size() != 3)
    pbrt_fail(p->where, "\"" + printable(p->declaration()) + "\" takes one triple");
  return std::array<double, 3>{p->numbers[0], p->numbers[1], p->numbers[2]};
}

std::vector<double> PbrtParameters::get_numbers(const std::string& name,
                                                const std::string& types) const {
  const PbrtParameter* p = find(name, types);
  return p ? p->numbers : std::vector<double>{};
}

void PbrtParameters::set_color_space(const std::string& space) {
  for (PbrtParameter& p : params_) p.color_space = space;
}

void PbrtParameters::add_defaults(const PbrtParameters& defaults) {
  for (const PbrtParameter& d : defaults.params_) {
    bool given = false;
    for (const PbrtParameter& p : params_) given = given || p.name == d.name;
    if (!given) {
      params_.push_back(d);
      params_.back().used = false;
    }
  }
}

void PbrtParameters::warn_unused(const std::string& what) const {
  for (const PbrtParameter& p : params_)
    if (!p.used)
      pbrt_warn(p.where,
                "\"" + printable(p.declaration()) + "\" of " + what + " is ignored by kasha");
}

}  // namespace kasha
