#include "render/option_table.h"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include "render/integrator_registry.h"

namespace kasha {

namespace {

using Group = std::pair<std::string, std::vector<std::string>>;  // a text and who gives it

void add_to(std::vector<Group>& groups, const std::string& text, const std::string& who) {
  for (Group& g : groups)
    if (g.first == text) return g.second.push_back(who);
  groups.push_back({text, {who}});
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// One help line from every declaration: "photon, ppm, vcm: radius reduction α (default 0.8)", or
// per integrator where they differ ("… (default: backward, debug 16; photon 8)").
std::string assembled_help(const std::vector<std::pair<std::string, IntegratorOption>>& decls) {
  std::vector<Group> helps, defaults;
  std::vector<std::string> takers;
  for (const auto& [who, d] : decls) {
    add_to(helps, d.help, who);
    add_to(defaults, d.fallback, who);
    takers.push_back(who);
  }
  std::string text;
  if (helps.size() == 1) text = joined(takers) + ": " + helps[0].first;
  for (size_t i = 0; helps.size() > 1 && i < helps.size(); ++i)
    text += (i ? "; " : "") + joined(helps[i].second) + ": " + helps[i].first;
  if (defaults.size() == 1) return text + " (default " + defaults[0].first + ")";
  text += " (default:";
  for (size_t i = 0; i < defaults.size(); ++i)
    text += (i ? "; " : " ") + joined(defaults[i].second) + " " + defaults[i].first;
  return text + ")";
}

// Where a setting lives, comparable between declarations.
const void* address_of(const IntegratorOption& option, IntegratorSettings& settings) {
  return std::visit(
      [](const auto& field) -> const void* {
        if constexpr (std::is_same_v<std::decay_t<decltype(field)>, ChoiceField>)
          return field.address;
        else
          return field;
      },
      option.field(settings));
}

void check_agree(const IntegratorOption& a, const IntegratorOption& b, const std::string& who) {
  IntegratorSettings s;
  if (a.value != b.value || a.lo != b.lo || a.hi != b.hi || a.device_own != b.device_own ||
      address_of(a, s) != address_of(b, s))
    throw std::logic_error(who + ": " + b.name + " is declared otherwise by another integrator");
}

std::vector<RenderOption> gather_options() {
  std::vector<std::string> order;
  std::vector<std::vector<std::pair<std::string, IntegratorOption>>> decls;
  for (const IntegratorInfo& info : IntegratorRegistry::all())
    for (const IntegratorOption& d : info.options) {
      size_t i = 0;
      while (i < order.size() && order[i] != d.name) ++i;
      if (i == order.size()) {
        order.push_back(d.name);
        decls.emplace_back();
      } else {
        check_agree(decls[i][0].second, d, info.name);
      }
      decls[i].push_back({info.name, d});
    }
  std::vector<RenderOption> table;
  for (const auto& ds : decls) {
    RenderOption o{ds[0].second, {}};
    o.option.help = assembled_help(ds);
    for (const auto& [who, d] : ds) o.takers.push_back(who);
    table.push_back(std::move(o));
  }
  for (IntegratorOption o : common_options()) {
    o.help += " (default " + o.fallback + ")";
    table.push_back({std::move(o), {}});
  }
  return table;
}

}  // namespace

const std::vector<RenderOption>& render_options() {
  static const std::vector<RenderOption> table = gather_options();  // the registry is full by now
  return table;
}

std::string settings_fingerprint(const IntegratorSettings& settings) {
  IntegratorSettings s = settings;  // the fields are writable ones
  std::string text;
  for (const RenderOption& o : render_options()) {
    if (o.option.device_own) continue;
    text += "|";
    std::visit(
        [&](const auto& field) {
          using T = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<T, ChoiceField>) {
            text += (*field.names)[field.get()];
          } else {
            char number[32];
            std::snprintf(number, sizeof number, "%.17g", static_cast<double>(*field));
            text += number;
          }
        },
        o.option.field(s));
  }
  return text;
}

}  // namespace kasha
