#pragma once
// A pbrt-v4 parameter list: `"float radius" 2 "rgb reflectance" [0.8 0.2 0.1] ...`. Each value
// is typed by its declaration; a directive takes the parameters it knows, each taking marks it
// used, and what nobody took is reported as ignored (pbrt-v4's ReportUnused, as a warning).
#include <optional>
#include <string>
#include <vector>

#include "scene/pbrt/pbrt_tokenizer.h"

namespace kasha {

struct PbrtParameter {
  std::string type;  // canonical: integer float point2 vector2 point3 vector3 normal3 spectrum
                     // rgb blackbody bool string texture
  std::string name;
  std::vector<double> numbers;       // numeric types, and a spectrum given as [λ v ...]
  std::vector<std::string> strings;  // string, texture, a spectrum named or in a file
  std::vector<bool> bools;
  PbrtLocation where;
  std::string color_space = "srgb";  // pbrt-v4's ColorSpace where it was given: its RGB's space
  mutable bool used = false;

  std::string declaration() const { return type + " " + name; }  // for messages
  size_t count() const;                                          // values given
};

class PbrtParameters {
 public:
  // Reads declarations and values until the next token that starts no declaration.
  static PbrtParameters read(PbrtTokenizer& tokens);

  // The parameter, marked used; nullptr when absent. A type other than one of `types` (space
  // separated) is an Error naming the parameter.
  const PbrtParameter* find(const std::string& name, const std::string& types) const;
  double get_float(const std::string& name, double fallback) const;
  int get_int(const std::string& name, int fallback) const;
  bool get_bool(const std::string& name, bool fallback) const;
  std::string get_string(const std::string& name, const std::string& fallback) const;
  // A point3/vector3/normal3 (one triple).
  std::optional<std::array<double, 3>> get_triple(const std::string& name) const;
  // Numbers of a numeric array parameter (`types` as for find); empty when absent.
  std::vector<double> get_numbers(const std::string& name, const std::string& types) const;

  // Marks every parameter as given in ColorSpace `space` (pbrt_color_space.h).
  void set_color_space(const std::string& space);

  // Adds the parameters of `defaults` that this list does not give (pbrt-v4's Attribute).
  void add_defaults(const PbrtParameters& defaults);

  // One warning per parameter nobody took: "FILE:LINE: `float foo` of Shape "sphere" ignored".
  void warn_unused(const std::string& what) const;

  const std::vector<PbrtParameter>& all() const { return params_; }

 private:
  std::vector<PbrtParameter> params_;
};

// A name from the file in quotes, printable (control bytes escaped), for messages.
std::string in_quotes(const std::string& s);

// "FILE:LINE: why" as a kasha::Error.
[[noreturn]] void pbrt_fail(const PbrtLocation& where, const std::string& why);
void pbrt_warn(const PbrtLocation& where, const std::string& why);

}  // namespace kasha
