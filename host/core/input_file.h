#pragma once
// The one way kasha opens an input file: regular files only (a directory, FIFO or device where a
// file is expected is refused up front, not read as empty or without end), within a size limit,
// every message naming the file.
#include <sys/stat.h>

#include <cstdint>
#include <string>

namespace kasha {

// Limits by kind: text that is parsed whole into memory (JSON scenes and materials, CSV tables)
// and binary inputs (OBJ meshes, EXR references). Far above any real input, far below what would
// exhaust memory.
constexpr std::uint64_t kMaxTextInputBytes = std::uint64_t(64) << 20;   // 64 MiB
constexpr std::uint64_t kMaxBinaryInputBytes = std::uint64_t(1) << 30;  // 1 GiB

// The whole content of `path`. Throws kasha::Error "PATH: why" when it is missing, unreadable,
// not a regular file, or larger than `max_bytes`.
std::string read_input_file(const std::string& path, std::uint64_t max_bytes);

// The same checks for a library that opens the file by name itself (OpenEXR).
void check_input_file(const std::string& path, std::uint64_t max_bytes);

// What a file of this mode is, for messages: "a directory", "a FIFO (pipe)", ...
std::string file_kind(mode_t mode);

}  // namespace kasha
