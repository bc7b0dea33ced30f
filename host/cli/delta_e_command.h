#pragma once
// `kasha delta-e`: the CIEDE2000 difference between two CIELAB colours.
#include <string>

namespace kasha {

int run_delta_e(const std::string& lab1, const std::string& lab2);

}  // namespace kasha
