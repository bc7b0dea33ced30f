#pragma once
// Output files appear whole or not at all: writers fill a temporary file next to the target,
// which is renamed over it only once complete.
#include <functional>
#include <string>

namespace kasha {

// Calls write(temporary_path); on success renames it to `path`, on any exception removes it and
// rethrows (kasha::Error naming `path` for non-kasha errors).
void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write);
// The same for a text that is ready in memory.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace kasha
