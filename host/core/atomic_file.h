#pragma once
// Output files appear whole or not at all: writers fill a temporary file next to the target,
// which is renamed over it only once complete; every stream is flushed and closed and both are
// checked, since a full disk shows only there.
#include <fstream>
#include <functional>
#include <string>

namespace kasha {

// Calls write(temporary_path); on success renames it to `path`, on any exception removes it and
// rethrows (kasha::Error naming `path` for non-kasha errors).
void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write);
// The same for a text that is ready in memory.
void write_text_atomically(const std::string& path, const std::string& text);

// Writes fill(stream) to `file` itself (no temporary: callers pass one), then flushes and closes
// it; throws kasha::Error naming `name` when opening, any write, the flush or the close failed.
void write_stream_file(const std::string& file, const std::string& name,
                       const std::function<void(std::ofstream&)>& fill);
// Flushes `out` and throws kasha::Error naming `name` if it has failed at any point.
void check_flushed(std::ostream& out, const std::string& name);

}  // namespace kasha
