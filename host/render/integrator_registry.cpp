#include "render/integrator_registry.h"

#include <algorithm>
#include <stdexcept>

#include "core/error.h"

namespace kasha {

std::vector<IntegratorInfo>& IntegratorRegistry::entries() {
  static std::vector<IntegratorInfo> registry;  // filled during static initialization
  return registry;
}

IntegratorRegistry::Registrar::Registrar(IntegratorInfo info) {
  // Its own options, each once: a common one is declared once for all (render/render_settings.h).
  for (size_t i = 0; i < info.options.size(); ++i) {
    const std::string& option = info.options[i].name;
    for (const IntegratorOption& common : common_options())
      if (common.name == option)
        throw std::logic_error(info.name + ": " + option + " is every integrator's");
    for (size_t j = 0; j < i; ++j)
      if (info.options[j].name == option)
        throw std::logic_error(info.name + ": " + option + " is declared twice");
  }
  auto& e = entries();
  e.insert(std::upper_bound(
               e.begin(), e.end(), info,
               [](const IntegratorInfo& a, const IntegratorInfo& b) { return a.name < b.name; }),
           std::move(info));
}

const std::vector<IntegratorInfo>& IntegratorRegistry::all() {
  return entries();
}

static std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

const IntegratorInfo& IntegratorRegistry::find(const std::string& name) {
  for (const IntegratorInfo& info : entries())
    if (info.name == name) return info;
  throw Error("unknown integrator \"" + name + "\" (" + join(names(false)) + ")");
}

std::vector<std::string> IntegratorRegistry::names(bool physical_only) {
  std::vector<std::string> out;
  for (const IntegratorInfo& info : entries())
    if (!physical_only || info.traits.physical) out.push_back(info.name);
  return out;
}

std::string IntegratorRegistry::reference() {
  for (const IntegratorInfo& info : entries())
    if (info.traits.reference) return info.name;
  throw Error("no reference integrator is registered");
}

std::unique_ptr<Integrator> IntegratorRegistry::make(const std::string& name,
                                                     const IntegratorSetup& setup) {
  std::unique_ptr<Integrator> integrator = find(name).make(setup);
  integrator->name_ = name;
  return integrator;
}

void IntegratorRegistry::check_options(const std::string& name,
                                       const std::vector<std::string>& given) {
  const IntegratorInfo& info = find(name);
  std::vector<std::string> takes;
  for (const IntegratorOption& option : info.options) takes.push_back(option.name);
  for (const std::string& option : given)
    if (std::find(takes.begin(), takes.end(), option) == takes.end())
      throw Error(option + ": the " + name + " integrator does not take this option" +
                  (takes.empty() ? std::string(" (it takes none of its own)")
                                 : " (it takes " + join(takes) + ")"));
}

}  // namespace kasha
