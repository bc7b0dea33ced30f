#pragma once
// Bytes from input (CSV cells, file names, EXR channel names, option values) as they may appear
// in a one-line message: control bytes, DEL, and bytes that are not valid UTF-8 become \xNN (and
// a backslash \\), so no input can break the line, move the cursor or fail a JSON writer.
#include <string>
#include <string_view>

namespace kasha {

std::string printable(std::string_view bytes);

// A message made safe for one line: control bytes and invalid UTF-8 escaped as \xNN (backslashes
// left alone: parts of the message may already be escaped).
std::string as_one_line(const std::string& message);

// Whether the bytes are valid UTF-8 (what nlohmann::json needs to write them).
bool valid_utf8(std::string_view bytes);

}  // namespace kasha
