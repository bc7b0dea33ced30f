#pragma once
// The files this process has opened for reading, so that outputs can be checked against the files
// a scene names (materials, CSVs, meshes) as well as against those on the command line.
#include <string>
#include <vector>

namespace kasha {

// Called by readers when they open a file (thread-safe).
void note_input_file(const std::string& path);
std::vector<std::string> input_files_read();
// Forgets them: each command line starts afresh (the fuzz harness runs many in one process).
void forget_input_files();

}  // namespace kasha
