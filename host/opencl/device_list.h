#pragma once
// `--device LIST`: one index (`0`), indices separated by commas (`0,1`) or `all`, as kasha's flat
// device indices (`kasha devices`). An index may be named twice: the same device twice (two
// queues on one device, so that several devices can be tested on one machine).
#include <cstddef>
#include <string>
#include <vector>

namespace kasha {

// The longest list: each entry is a render lane holding its own copy of the scene and film, so a
// list of thousands would exhaust memory before it rendered (`all` is every device, however many).
constexpr size_t kMaxDeviceListEntries = 64;

// What is wrong with the text as a list, or empty when it is one (no device is touched): the
// command line's check, so a malformed list is a usage error.
std::string device_list_syntax_error(const std::string& text);

// The indices, `all` expanded to every one of `device_count`; throws kasha::Error
// ("--device TEXT: ...") for malformed text or an index no device has.
std::vector<int> parse_device_list(const std::string& text, int device_count);
// The same against the devices this machine has.
std::vector<int> parse_device_list(const std::string& text);

}  // namespace kasha
