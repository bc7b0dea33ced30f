#pragma once
// Bytes from input (CSV cells, file names, EXR channel names, option values) as they may appear
// in a one-line message: control bytes, DEL, and bytes that are not valid UTF-8 become \xNN (and
// a backslash \\), so no input can break the line, move the cursor or fail a JSON writer.
#include <exception>
#include <string>
#include <string_view>
#include <system_error>

namespace kasha {

std::string printable(std::string_view bytes);

// A message made safe for one line: control bytes and invalid UTF-8 escaped as \xNN (backslashes
// left alone: parts of the message may already be escaped).
std::string as_one_line(const std::string& message);

// Whether the bytes are valid UTF-8 (what nlohmann::json needs to write them).
bool valid_utf8(std::string_view bytes);

// Bytes (a file name, a label) as a JSON string value, the one way every writer puts them there:
// valid UTF-8 without a backslash stays as it is (JSON escapes controls itself); anything else is
// printable(), whose backslashes are doubled, so the value is UTF-8 and no two inputs give the
// same.
std::string json_text(std::string_view bytes);

// A system error in the words of kasha's messages: "file name too long".
std::string error_words(const std::error_code& ec);

// What a library exception says, without the library's framing: a std::filesystem error as
// "PATH: words", nlohmann's without "[json.exception.type_error.316] "; one printable line.
std::string library_error_text(const std::exception& e);

}  // namespace kasha
