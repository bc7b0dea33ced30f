#pragma once
// gzip-compressed inputs as pbrt-v4 reads them: a file whose name ends in ".gz" (any case) is
// inflated whole (a .pbrt.gz scene or Include, a .ply.gz mesh); any other file is read as is.
#include <cstdint>
#include <string>

namespace kasha {

// True when `path` names a gzip file by pbrt-v4's rule (the name ends in ".gz", any case).
bool is_gzip_name(const std::string& path);

// The content of `path` (core/input_file.h's checks), inflated when is_gzip_name(path). Both the
// file and its inflated content are bounded by `max_bytes`: a small file that inflates past it
// (a "zip bomb") is refused, not allocated. Throws kasha::Error "PATH: why".
std::string read_input_file_inflated(const std::string& path, std::uint64_t max_bytes);

// Inflates gzip data (one member or several, one after another, as gzip writes them); `path`
// names it in messages.
std::string gunzip(const std::string& compressed, const std::string& path, std::uint64_t max_bytes);

}  // namespace kasha
