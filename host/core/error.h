#pragma once
// kasha's one error type: a message that is already one clear line (what, where, why), printed by
// the command line as is.
#include <stdexcept>
#include <string>

namespace kasha {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace kasha
