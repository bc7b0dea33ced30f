#pragma once
// `--device`: one device index, a comma-separated list of them (`0,1`; an index may repeat, which
// gives that device a second queue), or `all`.
#include <string>
#include <vector>

namespace kasha {

// Throws kasha::Error naming the option for text that is none of those or an index out of range.
std::vector<int> parse_device_list(const std::string& text);

}  // namespace kasha
