#pragma once
// One command-line option as an integrator declares it, beside its registration line (pbrt-v4:
// each integrator's Create reads its own parameters; Mitsuba 3: a plugin's properties documented
// beside it): its name, value kind and range, what it does and its default for that integrator,
// and where its value lives in IntegratorSettings. render/option_table.h gathers the declarations
// into the command line's options, the registry's refusal and the MPI fingerprint.
#include <cstdio>
#include <functional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "render/render_settings.h"

namespace kasha {

// An enumerated setting, read and written by its index into its names (choice_names<E>()).
struct ChoiceField {
  const void* address;  // the setting itself: two declarations of an option share it
  const std::vector<std::string>* names;
  std::function<size_t()> get;
  std::function<void(size_t)> set;
};

// Where a setting's value lives in IntegratorSettings.
using SettingField =
    std::variant<int*, long long*, unsigned*, unsigned long long*, double*, bool*, ChoiceField>;

template <typename T>
SettingField setting_field(T& value) {
  if constexpr (std::is_enum_v<T>) {
    return ChoiceField{&value, &choice_names<T>(), [&value] { return static_cast<size_t>(value); },
                       [&value](size_t i) { value = static_cast<T>(i); }};
  } else {
    return &value;
  }
}

// The field of a declaration: KASHA_SETTING(spp).
#define KASHA_SETTING(member) \
  [](::kasha::IntegratorSettings& s) { return ::kasha::setting_field(s.member); }

struct IntegratorOption {
  enum class Value {
    integer,    // within [lo, hi]
    number,     // finite, within [lo, hi]
    positive,   // finite, in (0, hi]
    bytes,      // bytes with an optional unit (512MiB, 2GB), within [lo, hi]
    flag,       // --name or --name=false
    choice,     // one of the enum's names (choice_names)
    depth_cap,  // an integer within [lo, hi], or `scene` (an int setting: kSceneDepthCap)
  };
  std::string name;  // --spp
  Value value;
  double lo = 0, hi = 0;
  std::string help;      // what it does in this integrator
  std::string fallback;  // its default in this integrator, as text (from the constants it uses)
  SettingField (*field)(IntegratorSettings&);
  bool device_own = false;  // a device's own (its memory): not part of what the image depends on
};

// A default for a declaration's text, from the constant the integrator uses: 0.8, 262144.
inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

}  // namespace kasha
